#pragma once
// One job at a time on a thread of its own, for work that must not wait in line behind the
// renderer's tasks nor be run by a thread that waits for something else (a task_group's wait()
// may pick up any queued task: the frame writer waiting for its EXR would encode the video
// itself, and the two would follow each other again). The thread sleeps between jobs.
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace sl {

class BackgroundWorker {
public:
    BackgroundWorker() : thread_([this] { loop(); }) {}
    BackgroundWorker(const BackgroundWorker&) = delete;
    BackgroundWorker& operator=(const BackgroundWorker&) = delete;
    ~BackgroundWorker() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        changed_.notify_all();
        thread_.join();  // a job still running ends first; its failure, unasked for, is dropped
    }

    // Waits for the job before (rethrowing its failure), then starts `job`.
    void run(std::function<void()> job) {
        wait();
        {
            std::lock_guard<std::mutex> lock(mutex_);
            job_ = std::move(job);
        }
        changed_.notify_all();
    }

    // Waits until no job is running; rethrows the failure of the last one, once.
    void wait() {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [this] { return !job_; });
        if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    }

private:
    void loop() {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            changed_.wait(lock, [this] { return stopping_ || job_; });
            if (!job_) return;  // stopping, nothing left to do
            lock.unlock();
            std::exception_ptr failure;
            try {
                job_();
            } catch (...) {
                failure = std::current_exception();
            }
            lock.lock();
            failure_ = failure;
            job_ = nullptr;
            changed_.notify_all();
        }
    }

    std::mutex mutex_;
    std::condition_variable changed_;
    std::function<void()> job_;  // the job running or about to run; empty when idle
    std::exception_ptr failure_;
    bool stopping_ = false;
    std::thread thread_;  // last: starts once everything above exists
};

}  // namespace sl
