// The extension module `meshreuse._meshreuse` (the package meshreuse/ wraps it): its errors as
// Python's -- a bad option or value ValueError (UsageError, InputError about a file's content), an
// unknown keyword TypeError, a file that cannot be read or written OSError (InputError about
// opening or reading, EnvironmentError) -- each with the command line's own message, and Ctrl-C
// honoured at progress points (PollSignals).
#include "cli/python/module.h"

#include <signal.h>

#include <atomic>
#include <boost/program_options/errors.hpp>

#include "core/error.h"

namespace meshreuse::python {

namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_depth{0};  // LongWork scopes open
struct sigaction g_python_handler;

extern "C" void NoteInterrupt(int) { g_interrupted.store(true); }

bool OnMainThread() {
  py::object threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace

LongWork::LongWork()
    : release_([this] {
        // Before the GIL goes (the member is built after this): decide and install.
        if (g_depth++ == 0 && OnMainThread()) {
          struct sigaction now {};
          ::sigaction(SIGINT, nullptr, &now);
          if (now.sa_handler != SIG_IGN && now.sa_handler != SIG_DFL) {
            g_interrupted.store(false);
            struct sigaction mine {};
            mine.sa_handler = NoteInterrupt;
            sigemptyset(&mine.sa_mask);
            ::sigaction(SIGINT, &mine, &g_python_handler);
            installed_ = true;
          }
        }
        return py::gil_scoped_release();
      }()) {}

LongWork::~LongWork() {
  // release_ is destroyed after this body: the GIL comes back then.
  if (installed_) {
    ::sigaction(SIGINT, &g_python_handler, nullptr);
    // Python's handler runs at its next check (raising KeyboardInterrupt); no GIL needed.
    if (g_interrupted.exchange(false)) PyErr_SetInterrupt();
  }
  --g_depth;
}

void PollSignals() {
  if (g_interrupted.load(std::memory_order_relaxed)) throw Interrupted();
}

void Warn(const std::string& what) {
  py::gil_scoped_acquire gil;
  if (PyErr_WarnEx(PyExc_UserWarning, what.c_str(), 1) != 0) throw py::error_already_set();
}

namespace {

bool AboutTheFileItself(const std::string& problem) {
  for (const char* p : {"cannot open", "cannot stat", "read error", "is a directory"})
    if (problem.rfind(p, 0) == 0) return true;
  return false;
}

}  // namespace

}  // namespace meshreuse::python

PYBIND11_MODULE(_meshreuse, m) {
  using namespace meshreuse;
  using namespace meshreuse::python;
  m.doc() = "meshreuse's C++ libraries (use the package `meshreuse`, which wraps this module)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(AboutTheFileItself(e.problem()) ? PyExc_OSError : PyExc_ValueError, e.what());
    } catch (const EnvironmentError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const boost::program_options::unknown_option& e) {
      PyErr_SetString(PyExc_TypeError, e.what());
    } catch (const boost::program_options::error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const Interrupted&) {
      // The interrupt was handed to Python's handler (LongWork): let it raise now.
      if (PyErr_CheckSignals() == 0) PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
  BindMesh(m);
  BindRunners(m);
}
