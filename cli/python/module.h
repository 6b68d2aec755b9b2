// The Python module's C++ side (pybind11): what its files share. The module only converts between
// Python (numpy arrays, keywords, exceptions) and the libraries; every algorithm is theirs.
//   mesh_module.cc  meshes from files or arrays, their arrays as zero-copy views, orderings,
//                   permutations, smoothing and the traced access stream;
//   run_module.cc   the runners (analyze, simulate, compare) from the commands' own option
//                   parsing (cli/configs.h), on files, meshes or ids in memory, their outputs as
//                   Python values;
//   module.cc       the module, its errors and Ctrl-C.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <memory>
#include <string>

#include "core/mesh.h"

namespace meshreuse::python {

namespace py = pybind11;

// A mesh as Python holds it: the C++ mesh and the name tables give it (its path, or "mesh").
struct PyMesh {
  std::shared_ptr<Mesh> mesh;
  std::string name;
  std::string path;  // the file it was read from ("" when built from arrays)
};

// Long work, for the scope of one object (constructed and destroyed holding the GIL): the GIL
// released and, when called on Python's main thread with Python's own SIGINT handler in place,
// SIGINT caught by a handler that only sets a flag (any thread's PollSignals sees it); on the way
// out the handler is put back and a Ctrl-C seen is handed to Python's (PyErr_SetInterrupt), which
// raises KeyboardInterrupt (or does what a user's handler does). Python's own handler cannot be
// asked from threads other than the main one, and the work runs on several.
class LongWork {
 public:
  LongWork();
  ~LongWork();
  LongWork(const LongWork&) = delete;
  LongWork& operator=(const LongWork&) = delete;

 private:
  bool installed_ = false;
  py::gil_scoped_release release_;
};

// What PollSignals throws after a Ctrl-C (the module turns it into Python's handling of SIGINT).
struct Interrupted : std::exception {
  const char* what() const noexcept override { return "interrupted"; }
};

// Throws Interrupted when a Ctrl-C arrived during long work; any thread, no GIL needed. Called at
// progress points: between batches of ids, at every progress line, every 2 s of reading.
void PollSignals();

// A UserWarning with `what` (takes the GIL); raises if the warning filter makes it an error.
void Warn(const std::string& what);

void BindMesh(py::module_& m);
void BindRunners(py::module_& m);

}  // namespace meshreuse::python
