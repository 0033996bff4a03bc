#pragma once
// A short first-in, first-out queue of additions to the section buffer's accumulators, kept by
// each thread of the camera pass across its pixels. With many frames a pixel's time slots span
// tens of KiB that the last pass left in main memory, so every deposit's read-modify-write
// waits on a cache miss; a pixel has only ~10 of them, too few to overlap much. Queued, each
// accumulator is prefetched when its deposit is made and added to about kCapacity deposits
// later, while the next pixels' rays are traced, so the misses are hidden behind that work.
// The additions happen in the order the deposits were made: every sum is the same, bit for bit,
// as adding at once.
#include <cstddef>

namespace sl {

class DepositQueue {
public:
    static constexpr size_t kCapacity = 64;  // a power of two; about six pixels' deposits

    DepositQueue() = default;
    DepositQueue(const DepositQueue&) = delete;
    DepositQueue& operator=(const DepositQueue&) = delete;
    ~DepositQueue() { drain(); }

    void add(float* acc, float r, float g, float b) {
        __builtin_prefetch(acc, 1);
        if (count_ == kCapacity) {
            apply(entries_[head_]);
            head_ = (head_ + 1) & (kCapacity - 1);
            --count_;
        }
        entries_[(head_ + count_) & (kCapacity - 1)] = Entry{acc, r, g, b};
        ++count_;
    }

    // Applies every queued addition, oldest first. Call before anything reads the accumulators
    // or adds to them without this queue.
    void drain() {
        for (; count_ > 0; --count_, head_ = (head_ + 1) & (kCapacity - 1)) apply(entries_[head_]);
        head_ = 0;
    }

private:
    struct Entry {
        float* acc;
        float r, g, b;
    };
    static void apply(const Entry& e) {
        e.acc[0] += e.r;
        e.acc[1] += e.g;
        e.acc[2] += e.b;
    }

    Entry entries_[kCapacity];
    size_t head_ = 0, count_ = 0;
};

}  // namespace sl
