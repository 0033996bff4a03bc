#pragma once
// Frame-sized float buffers that the write stage hands back to the assemble stage. A frame is
// megabytes: allocated afresh, each one was a new mapping (main.cpp sends blocks this large to
// mmap), so the kernel zeroed and faulted in every page of every frame, a fault per 4 KiB of
// video: at 192 frames of 256x256 that was most of the render's system time. The few frames
// alive at once (the graph's limiter) circulate instead, and their pages are touched once.
#include <mutex>
#include <utility>
#include <vector>

namespace sl {

class FrameBufferPool {
public:
    // A buffer with whatever size and contents it had (callers assign or overwrite all of it),
    // or an empty one when none is free.
    std::vector<float> take() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (free_.empty()) return {};
        std::vector<float> v = std::move(free_.back());
        free_.pop_back();
        return v;
    }
    // Kept for the next frame; beyond a few, freed (more are never alive at once).
    void give(std::vector<float>&& v) {
        if (v.capacity() == 0) return;
        std::lock_guard<std::mutex> lock(mutex_);
        if (free_.size() < kKeep) free_.push_back(std::move(v));
    }

private:
    static constexpr size_t kKeep = 8;
    std::mutex mutex_;
    std::vector<std::vector<float>> free_;
};

}  // namespace sl
