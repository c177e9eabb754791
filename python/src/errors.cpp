#include "errors.hpp"

#include <array>
#include <string>

#include "surfgrow/core/error.hpp"

namespace surfgrow::python {

namespace py = pybind11;

namespace {

struct ErrorClass {
    ErrorCode code;
    const char* name;
    PyObject* also;  // a built-in base, so `except ValueError` / `except OSError` work too
    const char* doc;
};

// The class for each ErrorCode; index 0 is surfgrow.Error itself.
std::array<PyObject*, 9> classes{};

}  // namespace

void bind_errors(py::module_& m) {
    PyObject* base = PyErr_NewExceptionWithDoc(
        "surfgrow.Error",
        "Every error surfgrow reports. `code` is the command line's exit code for it "
        "(README, \"When something is wrong\").",
        PyExc_Exception, nullptr);
    if (base == nullptr) throw py::error_already_set();
    classes[0] = base;
    m.attr("Error") = py::handle(base);
    const std::array<ErrorClass, 8> kinds{{
        {ErrorCode::kInternal, "InternalError", PyExc_RuntimeError,
         "A bug: an invariant did not hold. Please report it."},
        {ErrorCode::kUsage, "UsageError", PyExc_ValueError, "A malformed argument."},
        {ErrorCode::kInvalidParameter, "InvalidParameterError", PyExc_ValueError,
         "A value out of its valid range, or an array of the wrong shape or type."},
        {ErrorCode::kCannotOpen, "CannotOpenError", PyExc_OSError,
         "An input file is missing or unreadable."},
        {ErrorCode::kUnknownFormat, "UnknownFormatError", PyExc_ValueError,
         "A file whose format surfgrow cannot tell or does not support."},
        {ErrorCode::kMalformedInput, "MalformedInputError", PyExc_ValueError,
         "A file that claims a format but breaks it (bad header, truncated)."},
        {ErrorCode::kCannotWrite, "CannotWriteError", PyExc_OSError,
         "An output could not be written (permissions, disk full)."},
        {ErrorCode::kCloudTooLarge, "CloudTooLargeError", PyExc_ValueError,
         "The cloud cannot be indexed at this mu (extent / mu too large)."},
    }};
    py::setattr(base, "code", py::int_(1));
    for (const ErrorClass& k : kinds) {
        const std::string qualified = std::string("surfgrow.") + k.name;
        PyObject* bases = PyTuple_Pack(2, base, k.also);
        if (bases == nullptr) throw py::error_already_set();
        PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), k.doc, bases, nullptr);
        Py_DECREF(bases);
        if (cls == nullptr) throw py::error_already_set();
        py::setattr(cls, "code", py::int_(static_cast<int>(k.code)));
        classes[static_cast<std::size_t>(k.code)] = cls;
        m.attr(k.name) = py::handle(cls);
    }

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            const auto i = static_cast<std::size_t>(e.code());
            PyErr_SetString(i < classes.size() && classes[i] ? classes[i] : classes[0], e.what());
        } catch (const Interrupted&) {
            // Only reached if a binding forgot ProgressHook::rethrow(): still an interrupt.
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        }
    });
}

}  // namespace surfgrow::python
