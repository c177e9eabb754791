// An exception must not leave an OpenMP region: the runtime calls std::terminate. Loops whose
// body can throw (a bad parameter found deep inside, bad_alloc) run each iteration through
// ParallelErrors and rethrow after the loop, as if the loop had run on one thread.
#pragma once

#include <cstddef>
#include <exception>
#include <limits>
#include <mutex>

namespace surfgrow::detail {

class ParallelErrors {
  public:
    /// Runs body(); an exception it throws is kept if it comes from the lowest iteration so far,
    /// so the one rethrown does not depend on the thread count.
    template <class Body>
    void run(std::size_t iteration, Body&& body) noexcept {
        try {
            body();
        } catch (...) {
            const std::lock_guard<std::mutex> lock(mutex_);
            if (iteration < first_) {
                first_ = iteration;
                error_ = std::current_exception();
            }
        }
    }
    /// Rethrows the kept exception, if any (after the parallel loop).
    void rethrow() const {
        if (error_) std::rethrow_exception(error_);
    }

  private:
    std::mutex mutex_;
    std::size_t first_ = std::numeric_limits<std::size_t>::max();
    std::exception_ptr error_;
};

}  // namespace surfgrow::detail
