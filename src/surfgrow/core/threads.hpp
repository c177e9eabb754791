// How many worker threads a stage uses: the one place "threads = 0 means all cores" is resolved.
#pragma once

namespace surfgrow {

/// Threads per core beyond which more threads only cost memory and start-up (each has its own
/// stack and scratch): requests above kThreadsPerCore times the cores are clamped.
inline constexpr int kThreadsPerCore = 4;

/// The most threads a stage starts: kThreadsPerCore times the cores this process may use.
[[nodiscard]] int max_threads();

/// `requested` when positive; otherwise OpenMP's default team size (every core, or
/// OMP_NUM_THREADS where the user set it), at least 1; never more than max_threads() (a request
/// of 100000 threads would exhaust memory for stacks). Results never depend on it.
[[nodiscard]] int resolve_threads(int requested);

}  // namespace surfgrow
