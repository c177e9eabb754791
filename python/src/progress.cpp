#include "progress.hpp"

#include "errors.hpp"

namespace surfgrow::python {

namespace py = pybind11;

ProgressHook::ProgressHook(py::object callback) : callback_(std::move(callback)) {
    // progress=True: a bar on the terminal (tqdm when installed); False: none.
    if (py::isinstance<py::bool_>(callback_))
        callback_ = callback_.cast<bool>()
                        ? py::module_::import("surfgrow._progress").attr("terminal")()
                        : py::none();
    else if (!callback_.is_none() && !PyCallable_Check(callback_.ptr()))
        throw py::type_error("progress must be None, True, or a callable (stage, fraction)");
}

ProgressHook::~ProgressHook() {
    // error_already_set and the callback hold Python objects: drop them with the GIL held (the
    // hook lives in a binding, which holds it).
    error_.reset();
}

void ProgressHook::operator()(std::string_view stage, double fraction) {
    {
        py::gil_scoped_acquire gil;
        if (!error_) {
            try {
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                if (!callback_.is_none()) callback_(py::str(stage.data(), stage.size()), fraction);
            } catch (py::error_already_set& e) {
                error_.emplace(std::move(e));
            }
        }
        if (!error_) return;
    }
    // The grower catches what its progress callback throws inside its parallel loop and stops
    // after the slabs in flight (GrowerConfig::progress); every other report is outside one.
    throw Interrupted{};
}

std::function<void(std::string_view, double)> ProgressHook::function() {
    return [this](std::string_view stage, double fraction) { (*this)(stage, fraction); };
}

void ProgressHook::rethrow() {
    if (error_) {
        py::error_already_set e = std::move(*error_);
        error_.reset();
        throw e;
    }
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
}

}  // namespace surfgrow::python
