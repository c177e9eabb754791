// The kernels for x86-64 CPUs with AVX2 (compiled with -mavx2; used only where the CPU has it).
#define SURFGROW_KERNEL_TABLE kernel_table_avx2
#define SURFGROW_KERNEL_ISA "avx2"
#include "surfgrow/core/detail/simd_kernels_impl.hpp"
