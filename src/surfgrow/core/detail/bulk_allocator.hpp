// Allocation for the large per-point arrays (internal): no zero-fill, and huge pages where the OS
// offers them.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

namespace surfgrow::detail {

/// The huge-page size the bulk arrays are aligned to and advised for.
inline constexpr std::size_t kHugePage = std::size_t{2} << 20;

/// `v` rounded up to a multiple of kHugePage.
constexpr std::uintptr_t round_up_to_huge_page(std::uintptr_t v) {
    return (v + kHugePage - 1) / kHugePage * kHugePage;
}

/// `size` bytes (a multiple of kHugePage), 2 MiB-aligned, mapped on their own and advised for
/// huge pages (Linux; aligned_alloc elsewhere); nullptr when the OS refuses.
/// Big blocks are mapped directly rather than taken from malloc's heap, so that freeing one gives
/// its memory back to the OS at once: malloc keeps freed blocks of a size it has seen freed
/// before, and the peak resident memory of a run would count them.
[[nodiscard]] void* map_huge_pages(std::size_t size);
/// Frees a block of map_huge_pages(size).
void unmap_huge_pages(void* p, std::size_t size) noexcept;

/// Asks for huge pages on the 2 MiB-aligned part of [p, p + bytes), for memory not yet touched.
/// A hint, harmless where unsupported or where the memory is already in use.
void advise_huge_pages(const void* p, std::size_t bytes) noexcept;

/// Allocator for big arrays of trivial values (coordinates, keys, indices, labels).
///
/// - Elements are default-initialised, i.e. left as they are: vectors that are overwritten anyway
///   skip the memset that resize() would do.
/// - Blocks of 2 MiB or more are mapped on their own, 2 MiB-aligned and marked MADV_HUGEPAGE
///   (Linux), so first touch faults in 2 MiB pages instead of 4 KiB ones (in a virtual machine a
///   page fault costs microseconds; for a million points this saves tens of milliseconds), and
///   freeing one returns its memory to the OS at once.
template <class T>
struct BulkAllocator {
    using value_type = T;

    BulkAllocator() = default;
    template <class U>
    BulkAllocator(const BulkAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > (std::size_t(-1) - 2 * kHugePage) / sizeof(T)) throw std::bad_alloc();
        const std::size_t bytes = n * sizeof(T);
        void* p = nullptr;
        if (bytes >= kHugePage) {
            p = map_huge_pages(rounded(bytes));
        } else if constexpr (alignof(T) > alignof(std::max_align_t)) {
            // A type aligned to a cache line: malloc gives only max_align_t's alignment.
            const std::size_t a = alignof(T);
            p = std::aligned_alloc(a, (std::max<std::size_t>(bytes, 1) + a - 1) / a * a);
        } else {
            p = std::malloc(bytes ? bytes : 1);
        }
        if (!p) throw std::bad_alloc();
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        const std::size_t bytes = n * sizeof(T);
        if (bytes >= kHugePage)
            unmap_huge_pages(p, rounded(bytes));
        else
            std::free(p);
    }

    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;  // default-initialise: no zeroing
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    template <class U>
    bool operator==(const BulkAllocator<U>&) const noexcept {
        return true;
    }

  private:
    static std::size_t rounded(std::size_t bytes) { return round_up_to_huge_page(bytes); }
};

/// A vector of trivial values whose resize() does not zero-fill.
template <class T>
using BulkVector = std::vector<T, BulkAllocator<T>>;

/// Frees a vector's storage now. (`v = {}` would not: it assigns an empty list, keeping the
/// capacity.)
template <class Vector>
void release(Vector& v) noexcept {
    Vector().swap(v);
}

/// reserve() for a large std::vector about to be filled: its storage is faulted in 2 MiB pages
/// where the OS offers them (4 KiB page faults cost microseconds each in a virtual machine).
template <class Vector>
void reserve_bulk(Vector& v, std::size_t n) {
    const bool fresh = v.capacity() < n;
    v.reserve(n);
    if (fresh) advise_huge_pages(v.data(), n * sizeof(typename Vector::value_type));
}

}  // namespace surfgrow::detail
