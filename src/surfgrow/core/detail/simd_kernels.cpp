#include "surfgrow/core/detail/simd_kernels.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace surfgrow::detail {

extern const KernelTable kernel_table_baseline;
#if defined(SURFGROW_KERNELS_X86)
extern const KernelTable kernel_table_avx2;
extern const KernelTable kernel_table_avx512;
#endif

namespace {

bool cpu_has(const char* isa) {
    if (std::strcmp(isa, "baseline") == 0) return true;
#if defined(SURFGROW_KERNELS_X86)
    if (std::strcmp(isa, "avx2") == 0) return __builtin_cpu_supports("avx2");
    if (std::strcmp(isa, "avx512") == 0)
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
#endif
    return false;
}

const KernelTable* table_of(const char* isa) {
#if defined(SURFGROW_KERNELS_X86)
    if (std::strcmp(isa, "avx2") == 0) return &kernel_table_avx2;
    if (std::strcmp(isa, "avx512") == 0) return &kernel_table_avx512;
#endif
    return std::strcmp(isa, "baseline") == 0 ? &kernel_table_baseline : nullptr;
}

// The widest set the CPU has; SURFGROW_SIMD=<isa> caps it (to compare paths, or to rule one out).
const KernelTable* detect() {
    const char* cap = std::getenv("SURFGROW_SIMD");
    bool allowed = !cap || !*cap || !table_of(cap);
    for (const char* isa : {"avx512", "avx2", "baseline"}) {
        allowed = allowed || std::strcmp(isa, cap) == 0;
        if (allowed && cpu_has(isa)) return table_of(isa);
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
    return cpu_has(isa) ? table_of(isa) : nullptr;
}

KernelOverride::KernelOverride(const KernelTable& table)
    : previous_(g_override.exchange(&table, std::memory_order_acq_rel)) {}

KernelOverride::~KernelOverride() {
    g_override.store(previous_, std::memory_order_release);
}

}  // namespace surfgrow::detail
