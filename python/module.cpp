// The sylva Python module (docs/python.md): the library's scene loading, styles, renders and
// writers bound with pybind11. Sylva's InputError is a ValueError carrying the CLI's one line
// ("--set: ink.detail: ..."), a missing file a FileNotFoundError, a stop by Ctrl-C a
// KeyboardInterrupt.
#include "python/binding.h"

namespace sylva::python {

namespace {

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const Interrupted& e) {
    PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
  } catch (const InputError& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  }
}

}  // namespace

}  // namespace sylva::python

PYBIND11_MODULE(_sylva, m) {
  namespace sp = sylva::python;
  m.doc() =
      "Sylva: non-photorealistic renders of trees and plants (docs/python.md). Renders of one "
      "Scene run one at a time; different Scenes (each with its own GL context) render in "
      "parallel from several threads, the GIL released.";
  pybind11::register_exception_translator(&sp::translate);
  sp::bind_scene(m);
  sp::bind_render(m);
  sp::bind_styles(m);
  sp::bind_turntable(m);
}
