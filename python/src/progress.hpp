// Progress of a long call reaching Python, and Ctrl-C stopping it cleanly.
#pragma once

#include <pybind11/pybind11.h>

#include <functional>
#include <optional>
#include <string_view>

#include "errors.hpp"

namespace surfgrow::python {

/// The library's progress callback for one call made with the GIL released. Each report takes
/// the GIL, checks for a pending signal (Ctrl-C) and calls the user's callback (stage, fraction).
/// A KeyboardInterrupt, or an exception from the callback, is kept and the run is stopped by
/// throwing Interrupted from the report (the grower stops after the slabs in flight; nothing is
/// left half-built); rethrow() then raises it in Python.
class ProgressHook {
  public:
    /// `callback`: None, or a callable taking (stage: str, fraction: float).
    explicit ProgressHook(pybind11::object callback);
    ~ProgressHook();
    ProgressHook(const ProgressHook&) = delete;
    ProgressHook& operator=(const ProgressHook&) = delete;

    /// What GrowerConfig::progress (or a stage loop) calls.
    void operator()(std::string_view stage, double fraction);
    [[nodiscard]] std::function<void(std::string_view, double)> function();

    /// Runs `work` with the GIL released and returns its result; an Interrupted from it, or an
    /// error kept after the last report, is raised as the kept Python exception.
    template <class Work>
    auto run(Work&& work) {
        std::optional<decltype(work())> out;
        try {
            pybind11::gil_scoped_release release;
            out.emplace(work());
        } catch (const Interrupted&) {
            rethrow();
        }
        if (error_) rethrow();
        return std::move(*out);
    }

  private:
    [[noreturn]] void rethrow();
    pybind11::object callback_;
    std::optional<pybind11::error_already_set> error_;  // guarded by the GIL
};

}  // namespace surfgrow::python
