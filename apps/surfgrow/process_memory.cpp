#include "process_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace surfgrow::cli {

void keep_freed_memory() {
#if defined(__GLIBC__)
    // Blocks up to 256 MiB from the heap (a 10-million-point cloud's arrays), and up to 1 GiB
    // of free heap kept rather than trimmed.
    mallopt(M_MMAP_THRESHOLD, 256 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace surfgrow::cli
