#include "surfgrow/core/detail/simd_kernels.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace surfgrow::detail {

extern const KernelTable kernel_table_baseline;
#if defined(SURFGROW_KERNELS_X86)
extern const KernelTable kernel_table_avx2;
#endif
#if defined(SURFGROW_KERNELS_AVX512)
extern const KernelTable kernel_table_avx512;
#endif

namespace {

struct Path {
    const KernelTable* table;
    bool (*cpu_has)();
};

// Widest first.
const Path kPaths[] = {
#if defined(SURFGROW_KERNELS_AVX512)
    {&kernel_table_avx512,
     [] {
         return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
     }},
#endif
#if defined(SURFGROW_KERNELS_X86)
    {&kernel_table_avx2, [] { return bool(__builtin_cpu_supports("avx2")); }},
#endif
    {&kernel_table_baseline, [] { return true; }},
};

const Path* path_of(const char* isa) {
    for (const Path& p : kPaths)
        if (std::strcmp(p.table->isa, isa) == 0) return &p;
    return nullptr;
}

// The widest set the CPU has; SURFGROW_SIMD=<isa> caps it (to compare paths, or to rule one out).
const KernelTable* detect() {
    const char* cap = std::getenv("SURFGROW_SIMD");
    bool allowed = !cap || !path_of(cap);
    for (const Path& p : kPaths) {
        allowed = allowed || std::strcmp(p.table->isa, cap) == 0;
        if (allowed && p.cpu_has()) return p.table;
    }
    return &kernel_table_baseline;
}

std::atomic<const KernelTable*> g_override{nullptr};

}  // namespace

const KernelTable& kernels() {
    if (const KernelTable* t = g_override.load(std::memory_order_acquire)) return *t;
    static const KernelTable* const chosen = detect();
    return *chosen;
}

const KernelTable* kernels_for(const char* isa) {
    const Path* p = path_of(isa);
    return p && p->cpu_has() ? p->table : nullptr;
}

KernelOverride::KernelOverride(const KernelTable& table)
    : previous_(g_override.exchange(&table, std::memory_order_acq_rel)) {}

KernelOverride::~KernelOverride() {
    g_override.store(previous_, std::memory_order_release);
}

}  // namespace surfgrow::detail
