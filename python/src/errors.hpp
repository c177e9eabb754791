// surfgrow.Error and its subclasses, one per ErrorCode (the command line's exit codes).
#pragma once

#include <pybind11/pybind11.h>

namespace surfgrow::python {

/// Creates the exception classes in `m` and translates surfgrow::Error into them.
void bind_errors(pybind11::module_& m);

/// Thrown through the library by a progress hook to stop a run (Ctrl-C, or the Python callback
/// raised); ProgressHook::rethrow() turns it back into the Python exception.
struct Interrupted {};

}  // namespace surfgrow::python
