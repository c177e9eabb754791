#include "surfgrow/core/detail/bulk_allocator.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace surfgrow::detail {

void* map_huge_pages(std::size_t size) {
#if defined(__linux__)
    void* raw = ::mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) return nullptr;
    const auto a = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = round_up_to_huge_page(a);
    const std::size_t head = aligned - a;
    if (head > 0) ::munmap(raw, head);
    if (kHugePage - head > 0) ::munmap(reinterpret_cast<void*>(aligned + size), kHugePage - head);
#if defined(MADV_HUGEPAGE)
    ::madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);  // a hint
#endif
    return reinterpret_cast<void*>(aligned);
#else
    return std::aligned_alloc(kHugePage, size);
#endif
}

void unmap_huge_pages(void* p, [[maybe_unused]] std::size_t size) noexcept {
#if defined(__linux__)
    ::munmap(p, size);
#else
    std::free(p);
#endif
}

void advise_huge_pages([[maybe_unused]] const void* p,
                       [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const auto a = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t first = round_up_to_huge_page(a),
                         last = (a + bytes) / kHugePage * kHugePage;
    if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
}

}  // namespace surfgrow::detail
