#pragma once
// An allocator for the section buffer's time slots: blocks of 2 MiB and more are mapped at a
// 2 MiB boundary and offered to the kernel as transparent huge pages. The time-bucket scatter
// adds each photon to a slot chosen by its arrival time, anywhere in a pixel tile's slots; with
// hundreds of frames those slots span ~150 MB, and with 4 KiB pages nearly every deposit also
// missed the TLB. Huge pages need 512x fewer page faults to fill, too. Where the kernel keeps
// them off (THP "never"), this is an ordinary anonymous mapping.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <new>

namespace sl {

template <class T>
struct HugePageAllocator {
    using value_type = T;
    static constexpr size_t kHuge = size_t(2) << 20;

    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) {}

    T* allocate(size_t n) {
        const size_t bytes = n * sizeof(T);
        if (bytes < kHuge) {
            if (void* p = ::operator new(bytes, std::nothrow)) return static_cast<T*>(p);
            throw std::bad_alloc();
        }
        const size_t size = round_up(bytes);
        // Map one huge page more than needed, keep the 2 MiB-aligned part, return the rest.
        void* raw = mmap(nullptr, size + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (raw == MAP_FAILED) throw std::bad_alloc();
        const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
        const uintptr_t aligned = (start + kHuge - 1) & ~(kHuge - 1);
        if (aligned > start) munmap(raw, aligned - start);
        const uintptr_t tail = aligned + size, end = start + size + kHuge;
        if (end > tail) munmap(reinterpret_cast<void*>(tail), end - tail);
        madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);
        return reinterpret_cast<T*>(aligned);
    }

    void deallocate(T* p, size_t n) noexcept {
        const size_t bytes = n * sizeof(T);
        if (bytes < kHuge) ::operator delete(p);
        else munmap(p, round_up(bytes));
    }

    template <class U>
    bool operator==(const HugePageAllocator<U>&) const { return true; }
    template <class U>
    bool operator!=(const HugePageAllocator<U>&) const { return false; }

private:
    static size_t round_up(size_t bytes) { return (bytes + kHuge - 1) & ~(kHuge - 1); }
};

}  // namespace sl
