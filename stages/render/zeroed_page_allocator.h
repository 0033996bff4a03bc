#pragma once
// An allocator for the section buffer's time slots whose memory comes zeroed: blocks of 2 MiB
// and more are fresh anonymous mappings (zero by definition, and handed back to the system
// whole when freed), smaller ones are zeroed once. So
// value-initialising an element does nothing: a std::vector sized with it is not filled a
// second time, and the buffer's pages are first touched where the section buffer chooses (by
// every thread). A vector using it must not shrink and grow again (elements regrown in the old
// capacity would keep their old values); the section buffer is sized once.
//
// The mapping is deliberately left on ordinary 4 KiB pages. Transparent huge pages saved TLB
// misses in the time-bucket scatter, but on the virtual machines this was measured on the host
// takes back free 2 MiB blocks, and a fresh process faulting 150 MB of huge pages back in spent
// 0.7-1.1 s in the kernel against 0.08-0.17 s with small pages (docs/benchmarks.md).
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <utility>

namespace sl {

template <class T>
struct ZeroedPageAllocator {
    using value_type = T;
    static constexpr size_t kMapped = size_t(2) << 20;  // from here on, a mapping of its own

    ZeroedPageAllocator() = default;
    template <class U>
    ZeroedPageAllocator(const ZeroedPageAllocator<U>&) {}

    T* allocate(size_t n) {
        const size_t bytes = n * sizeof(T);
        if (bytes < kMapped) {
            if (void* p = ::operator new(bytes, std::nothrow)) return static_cast<T*>(std::memset(p, 0, bytes));
            throw std::bad_alloc();
        }
        void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        return static_cast<T*>(p);
    }

    void deallocate(T* p, size_t n) noexcept {
        const size_t bytes = n * sizeof(T);
        if (bytes < kMapped) ::operator delete(p);
        else munmap(p, bytes);  // the kernel rounds to whole pages, as mmap did
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
    bool operator==(const ZeroedPageAllocator<U>&) const { return true; }
    template <class U>
    bool operator!=(const ZeroedPageAllocator<U>&) const { return false; }
};

}  // namespace sl
