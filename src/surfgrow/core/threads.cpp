#include "surfgrow/core/threads.hpp"

#include <omp.h>

#include <algorithm>

namespace surfgrow {

int max_threads() {
    return kThreadsPerCore * std::max(1, omp_get_num_procs());
}

int resolve_threads(int requested) {
    const int wanted = requested > 0 ? requested : std::max(1, omp_get_max_threads());
    return std::min(wanted, max_threads());
}

}  // namespace surfgrow
