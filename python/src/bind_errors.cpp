// C++ errors as Python exceptions with the C++ message: InputError is also a ValueError, BackendError
// a RuntimeError, both subclasses of depthtrack.Error.
#include <depthtrack/error.hpp>

#include "bindings.hpp"

namespace depthtrack::python {

void bind_errors(py::module_& m) {
  // Never destroyed: a static Python object would be released after the interpreter is gone.
  static const auto* error = new py::exception<Error>(m, "Error", PyExc_RuntimeError);
  static const auto* input_error =
      new py::exception<InputError>(m, "InputError", py::make_tuple(*error, py::handle(PyExc_ValueError)));
  static const auto* backend_error = new py::exception<BackendError>(m, "BackendError", *error);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error->ptr(), e.what());
    } catch (const BackendError& e) {
      PyErr_SetString(backend_error->ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(error->ptr(), e.what());
    }
  });
}

}  // namespace depthtrack::python
