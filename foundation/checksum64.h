#pragma once
// A 64-bit checksum in the manner of xxHash64 (four lanes of multiply-rotate, several GB/s),
// streamed: what it covers is never held in memory as a whole. Checkpoints checksum their
// payload with it and EXR frames their pixels; a byte-at-a-time hash cost a 256x256 frame
// about 1 ms on the thread that writes it.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace sl {

class Checksum64 {
public:
    void update(const void* data, size_t n) {
        if (n == 0) return;  // (data may then be null, which memcpy must never be given)
        auto* p = static_cast<const unsigned char*>(data);
        total_ += n;
        if (held_ > 0) {
            size_t take = std::min(n, sizeof block_ - held_);
            std::memcpy(block_ + held_, p, take);
            held_ += take, p += take, n -= take;
            if (held_ < sizeof block_) return;
            mix(block_);
            held_ = 0;
        }
        for (; n >= sizeof block_; p += sizeof block_, n -= sizeof block_) mix(p);
        std::memcpy(block_, p, n);
        held_ = n;
    }
    uint64_t value() const {
        uint64_t h = rotl(lane_[0], 1) + rotl(lane_[1], 7) + rotl(lane_[2], 12) + rotl(lane_[3], 18);
        h ^= total_ * kP5;
        for (size_t i = 0; i < held_; ++i) h = rotl(h ^ (block_[i] * kP5), 11) * kP1;
        h ^= h >> 33, h *= kP2, h ^= h >> 29, h *= kP3, h ^= h >> 32;
        return h;
    }

private:
    static constexpr uint64_t kP1 = 11400714785074694791ull, kP2 = 14029467366897019727ull,
                              kP3 = 1609587929392839161ull, kP5 = 2870177450012600261ull;
    static uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
    void mix(const unsigned char* p) {
        for (int k = 0; k < 4; ++k) {
            uint64_t w;
            std::memcpy(&w, p + 8 * k, 8);
            lane_[k] = rotl(lane_[k] + w * kP2, 31) * kP1;
        }
    }
    uint64_t lane_[4] = {kP1 + kP2, kP2, 0, 0 - kP1};
    unsigned char block_[32] = {};
    size_t held_ = 0;
    uint64_t total_ = 0;
};

}  // namespace sl
