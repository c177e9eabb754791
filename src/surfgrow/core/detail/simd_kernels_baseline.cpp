// The kernels with the build's own flags: SSE2 on a portable x86-64 build, NEON on aarch64.
#define SURFGROW_KERNEL_TABLE kernel_table_baseline
#define SURFGROW_KERNEL_ISA "baseline"
#include "surfgrow/core/detail/simd_kernels_impl.hpp"
