// The Python module `stairplan._stairplan` (re-exported by the package `stairplan`): the version,
// the exception translation, and the areas bound in their own translation units.
#include <cerrno>
#include <cstring>

#include "bindings.h"
#include "stairplan/geometry/field_error.h"
#include "stairplan/version.h"

namespace stairplan::python {
namespace {

void TranslateExceptions(py::module_& m) {
  // FieldError is a ValueError naming the field; `field` holds the field alone.
  static py::exception<FieldError> field_error(m, "FieldError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const FileNotFound& e) {
      py::object exc = py::reinterpret_steal<py::object>(PyObject_CallFunction(
          PyExc_FileNotFoundError, "iss", ENOENT, std::strerror(ENOENT), e.path().c_str()));
      if (exc) PyErr_SetObject(PyExc_FileNotFoundError, exc.ptr());
    } catch (const FieldError& e) {
      py::object exc = py::handle(field_error.ptr())(e.what());
      exc.attr("field") = e.field();
      PyErr_SetObject(field_error.ptr(), exc.ptr());
    }
  });
}

}  // namespace
}  // namespace stairplan::python

PYBIND11_MODULE(_stairplan, m) {
  namespace sp = stairplan::python;
  m.doc() = "stairplan: optimisation-centric stair planning for legged robots (C++ core, pybind11).";
  m.attr("__version__") = stairplan::kVersion;
  m.attr("schema_version") = stairplan::kSchemaVersion;
  sp::TranslateExceptions(m);
  sp::BindGeometry(m);
  sp::BindPlan(m);
  sp::BindSweep(m);
  sp::BindOptim(m);
  sp::BindBody(m);
}
