// How many worker threads a stage uses: the one place "threads = 0 means all cores" is resolved.
#pragma once

namespace surfgrow {

/// `requested` when positive; otherwise OpenMP's default team size (every core, or
/// OMP_NUM_THREADS where the user set it), at least 1. Results never depend on it.
[[nodiscard]] int resolve_threads(int requested);

}  // namespace surfgrow
