// How the surfgrow process asks the C library to manage its memory.
#pragma once

namespace surfgrow::cli {

/// Keeps the memory a stage frees for the stages after it, instead of returning it to the
/// kernel: glibc hands blocks above its mmap threshold back at once, and the next stage's
/// allocation of the same size then faults in freshly zeroed pages (on a 12-scan map 10-20 % of
/// the run). Memory is returned at exit; the peak is what the largest stage needed. The library
/// never does this: it is the process's choice. No effect outside glibc.
void keep_freed_memory();

}  // namespace surfgrow::cli
