// The Python module `filum`: scenes loaded from files or dicts, stepped from Python,
// their state read and written as NumPy arrays, frames rendered to arrays. Documentation:
// docs/python.md. Exceptions:
//   filum.SceneError (ValueError)     a scene that does not load, naming the file and JSON path;
//   filum.StepError (RuntimeError)    a step that failed (the scene rolled back to before it);
//   filum.RenderingError (RuntimeError) no rendering in this build or on this machine.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/visual/offscreen_renderer.hpp"

PYBIND11_MODULE(filum, m) {
  namespace py = pybind11;
  m.doc() = "filum: real-time simulation of one-dimensional deformable bodies (threads, catheters)";
  py::register_exception<filum::SceneError>(m, "SceneError", PyExc_ValueError);
  py::register_exception<filum::python::StepFailure>(m, "StepError", PyExc_RuntimeError);
  py::register_exception<filum::python::RenderingUnavailable>(m, "RenderingError", PyExc_RuntimeError);
  // False when this build has no OpenCV (FILUM_WITH_OPENCV=OFF): Scene.render() then raises.
  m.attr("rendering_available") = filum::visual::renderingAvailable();
  filum::python::bindState(m);
  filum::python::bindBody(m);
  filum::python::bindScene(m);
}
