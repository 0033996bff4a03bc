#pragma once
// An allocator for the section buffer's time slots: blocks of 2 MiB and more are mapped at a
// 2 MiB boundary and offered to the kernel as transparent huge pages. The time-bucket scatter
// adds each photon to a slot chosen by its arrival time, anywhere in a pixel tile's slots; with
// hundreds of frames those slots span ~150 MB, and with 4 KiB pages nearly every deposit also
// missed the TLB. Huge pages need 512x fewer page faults to fill, too. Where the kernel keeps
// them off (THP "never"), this is an ordinary anonymous mapping.
//
// Its memory comes zeroed (a fresh mapping is), so value-initialising an element does nothing:
// a std::vector sized with it is not filled a second time, the buffer's pages are first touched
// where the section buffer chooses (by both threads). A vector using it must not shrink and grow
// again (elements regrown in the old capacity would keep their old values); the section buffer
// is sized once.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <utility>

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
            if (void* p = ::operator new(bytes, std::nothrow)) return static_cast<T*>(std::memset(p, 0, bytes));
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

    // Value-initialisation (T()) leaves allocate()'s zeros; anything else is constructed.
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    template <class U>
    bool operator==(const HugePageAllocator<U>&) const { return true; }
    template <class U>
    bool operator!=(const HugePageAllocator<U>&) const { return false; }

private:
    static size_t round_up(size_t bytes) { return (bytes + kHuge - 1) & ~(kHuge - 1); }
};

}  // namespace sl
