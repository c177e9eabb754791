// The kernels for x86-64 CPUs with AVX-512 (F, VL, BW, DQ): the same 8 lanes as every path, with
// mask registers for the masked sums (used only where the CPU has them).
#define SURFGROW_KERNEL_TABLE kernel_table_avx512
#define SURFGROW_KERNEL_ISA "avx512"
#include "surfgrow/core/detail/simd_kernels_impl.hpp"
