#include "surfgrow/core/threads.hpp"

#include <omp.h>

#include <algorithm>

namespace surfgrow {

int resolve_threads(int requested) {
    return requested > 0 ? requested : std::max(1, omp_get_max_threads());
}

}  // namespace surfgrow
