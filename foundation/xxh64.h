#pragma once
// XXH64 (seed 0) from libxxhash, streamed: what it covers is never held in memory as a whole.
// Checkpoints checksum their header and payload with it and EXR frames their pixels; being the
// published algorithm, `xxhsum -H1` reproduces a checkpoint's sums (docs/checkpoints.md).
#include <xxhash.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

namespace sl {

// XXH64 (seed 0) of a few bytes at once: a hash table's key.
inline uint64_t xxh64_of(const void* data, size_t n) { return XXH64(data, n, 0); }

class Xxh64 {
public:
    Xxh64() : state_(XXH64_createState()) {
        if (!state_ || XXH64_reset(state_.get(), 0) != XXH_OK) throw std::bad_alloc();
    }
    void update(const void* data, size_t n) {
        if (n > 0) XXH64_update(state_.get(), data, n);  // (data may then be null)
    }
    uint64_t value() const { return XXH64_digest(state_.get()); }

private:
    struct Free {
        void operator()(XXH64_state_t* s) const { XXH64_freeState(s); }
    };
    std::unique_ptr<XXH64_state_t, Free> state_;
};

}  // namespace sl
