// Meshes, orderings, smoothing and the traced access stream for Python (module.h). A mesh's arrays
// are numpy views of the C++ arrays (no copy; read-only, since the adjacency and the boundary are
// derived from them and a write would break the mesh's invariants); arrays handed to C++ are
// checked by the same code as a file's (BuildMesh, Permutation::FromNewToOld), with the same
// messages. Long work runs with the GIL released.
#include <cstddef>
#include <cstring>
#include <vector>

#include "cli/python/module.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "core/mesh_io.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "core/progress.h"
#include "core/quality.h"
#include "core/schedule.h"
#include "core/smoother.h"
#include "tracer/access_stream.h"

namespace meshreuse::python {

namespace {

// A read-only view of `n` x `cols` items at `data`, kept alive by `owner` (the Python object).
template <class T>
py::array View(const T* data, size_t n, size_t cols, py::handle owner) {
  std::vector<py::ssize_t> shape = {static_cast<py::ssize_t>(n)},
                           strides = {static_cast<py::ssize_t>(cols * sizeof(T))};
  if (cols > 1) shape.push_back(static_cast<py::ssize_t>(cols)), strides.push_back(sizeof(T));
  py::array a(py::dtype::of<T>(), shape, strides, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// A vector handed to numpy without a copy: the array owns it (a capsule deletes it).
template <class T>
py::array Give(std::vector<T>&& v) {
  auto* held = new std::vector<T>(std::move(v));
  py::capsule free(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(held->size()), held->data(), free);
}

// Progress of a long phase (reading, writing) checks for Ctrl-C (core/progress.h: at most every
// 2 s once the phase has lasted 2 s).
ProgressListener PollingListener() {
  return [](const std::string&, uint64_t, uint64_t, double) { PollSignals(); };
}

PyMesh ReadPyMesh(const std::string& path) {
  std::vector<std::string> warnings;
  PyMesh m;
  {
    LongWork work;
    PhaseProgress phase("reading " + path, PollingListener());
    m.mesh = std::make_shared<Mesh>(ReadMesh(path, &warnings));
  }
  for (const std::string& w : warnings) Warn(w);
  m.name = m.path = path;
  return m;
}

// A mesh from numpy: points (n, 2) float64, triangles (m, 3) integers (0-based), checked by
// BuildMesh as a file's would be (unused points dropped, with a warning).
PyMesh MeshFromArrays(py::array_t<double, py::array::c_style | py::array::forcecast> points,
                      py::array_t<int64_t, py::array::c_style | py::array::forcecast> triangles,
                      const std::string& name) {
  if (points.ndim() != 2 || points.shape(1) != 2) throw UsageError("points must have shape (n, 2)");
  if (triangles.ndim() != 2 || triangles.shape(1) != 3)
    throw UsageError("triangles must have shape (m, 3)");
  const int64_t n = points.shape(0), t = triangles.shape(0);
  if (n > INT32_MAX || t > INT32_MAX / 3) throw UsageError("more than 2^31-1 points or ids");
  RawMesh raw;
  raw.vertex_file = name + " points";
  raw.triangle_file = name + " triangles";
  raw.xy.resize(static_cast<size_t>(2 * n));
  if (n) std::memcpy(raw.xy.data(), points.data(), static_cast<size_t>(2 * n) * sizeof(double));
  raw.tri.resize(static_cast<size_t>(3 * t));
  const int64_t* c = triangles.data();
  for (int64_t i = 0; i < 3 * t; ++i) {
    if (c[i] < 0 || c[i] >= n)
      throw InputError(raw.triangle_file, 0,
                       "triangle " + std::to_string(i / 3) + " has corner " + std::to_string(c[i]) +
                           ", not a point index 0.." + std::to_string(n - 1));
    raw.tri[static_cast<size_t>(i)] = static_cast<int32_t>(c[i]);
  }
  for (int64_t i = 0; i < n; ++i) raw.vertex_line.Push(i);  // messages name the row
  for (int64_t i = 0; i < t; ++i) raw.triangle_line.Push(i);
  BuildReport report;
  PyMesh m;
  m.mesh = std::make_shared<Mesh>(BuildMesh(std::move(raw), &report));
  for (const std::string& w : report.warnings) Warn(w);
  m.name = name;
  return m;
}

Permutation PermutationOf(const PyMesh& m,
                          py::array_t<int64_t, py::array::c_style | py::array::forcecast> perm) {
  if (perm.ndim() != 1) throw UsageError("a permutation is one-dimensional: new id -> old id");
  if (perm.shape(0) != m.mesh->NumVertices())
    throw UsageError("a permutation of " + std::to_string(perm.shape(0)) + " ids for a mesh of " +
                     std::to_string(m.mesh->NumVertices()) + " vertices");
  std::vector<int32_t> v(static_cast<size_t>(perm.shape(0)));
  for (size_t i = 0; i < v.size(); ++i) {
    const int64_t x = perm.data()[i];
    if (x < 0 || x > INT32_MAX)
      throw UsageError("permutation entry " + std::to_string(i) + " is " + std::to_string(x) +
                       ", not a vertex id");
    v[i] = static_cast<int32_t>(x);
  }
  return Permutation::FromNewToOld(std::move(v));  // std::invalid_argument: ValueError
}

// The access stream of `iterations` exact sweeps of the mesh laid out in `ordering`, in the order
// the analyzer receives it.
class Collect : public AccessConsumer {
 public:
  void Begin(const StreamInfo& info) override {
    uint64_t n = 0;
    for (const auto& s : info.sweep_records)
      for (uint64_t r : s) n += r;
    out.reserve(n);
  }
  void Consume(const Access* a, size_t n) override { out.insert(out.end(), a, a + n); }
  std::vector<Access> out;
};

py::dict SweepDict(const SmoothResult& r) {
  std::vector<double> quality, improvement, seconds, cpu;
  for (const SweepRecord& s : r.sweeps) {
    quality.push_back(s.quality), improvement.push_back(s.improvement);
    seconds.push_back(s.seconds), cpu.push_back(s.cpu_seconds);
  }
  py::dict d;
  d["sweeps"] = r.sweeps.size();
  d["quality"] = Give(std::move(quality));
  d["improvement"] = Give(std::move(improvement));
  d["seconds"] = Give(std::move(seconds));
  d["cpu_seconds"] = Give(std::move(cpu));
  d["quality_before"] = r.quality_before;
  d["quality_after"] = r.quality_after;
  d["converged"] = r.converged;
  return d;
}

}  // namespace

void BindMesh(py::module_& m) {
  static_assert(sizeof(Access) == 24, "numpy's access dtype");
  PYBIND11_NUMPY_DTYPE(Access, address, element, size, thread, kind, array, write);
  py::class_<PyMesh>(m, "Mesh")
      .def_static("read", &ReadPyMesh, py::arg("path"))
      .def(py::init(&MeshFromArrays), py::arg("points"), py::arg("triangles"),
           py::arg("name") = "mesh")
      .def_readonly("name", &PyMesh::name)
      .def_readonly("path", &PyMesh::path)
      .def_property_readonly("num_vertices", [](const PyMesh& p) { return p.mesh->NumVertices(); })
      .def_property_readonly("num_triangles",
                             [](const PyMesh& p) { return p.mesh->NumTriangles(); })
      .def_property_readonly("num_boundary", [](const PyMesh& p) { return p.mesh->NumBoundary(); })
      .def_property_readonly("points",
                             [](py::object self) {
                               const Mesh& x = *self.cast<const PyMesh&>().mesh;
                               return View(x.xy.data(), x.xy.size() / 2, 2, self);
                             })
      .def_property_readonly("triangles",
                             [](py::object self) {
                               const Mesh& x = *self.cast<const PyMesh&>().mesh;
                               return View(x.tri.data(), x.tri.size() / 3, 3, self);
                             })
      .def_property_readonly("boundary",
                             [](py::object self) {
                               const Mesh& x = *self.cast<const PyMesh&>().mesh;
                               return View(x.boundary.data(), x.boundary.size(), 1, self);
                             })
      .def_property_readonly("interior",
                             [](py::object self) {
                               const Mesh& x = *self.cast<const PyMesh&>().mesh;
                               return View(x.interior.data(), x.interior.size(), 1, self);
                             })
      .def_property_readonly("neighbours",
                             [](py::object self) {
                               const Mesh& x = *self.cast<const PyMesh&>().mesh;
                               return py::make_tuple(
                                   View(x.v2v.off.data(), x.v2v.off.size(), 1, self),
                                   View(x.v2v.idx.data(), x.v2v.idx.size(), 1, self));
                             })
      .def_property_readonly("vertex_triangles",
                             [](py::object self) {
                               const Mesh& x = *self.cast<const PyMesh&>().mesh;
                               return py::make_tuple(
                                   View(x.v2t.off.data(), x.v2t.off.size(), 1, self),
                                   View(x.v2t.idx.data(), x.v2t.idx.size(), 1, self));
                             })
      .def("quality", [](const PyMesh& p) { return GlobalQuality(*p.mesh); })
      .def("triangle_qualities", [](const PyMesh& p) { return Give(TriangleQualities(*p.mesh)); })
      .def("vertex_qualities", [](const PyMesh& p) { return Give(VertexQualities(*p.mesh)); })
      .def(
          "ordering",
          [](const PyMesh& p, const std::string& spec, uint64_t seed) {
            const OrderingSpec s = ParseOrderingSpec(spec);
            std::vector<int32_t> v;
            {
              LongWork work;
              v = ComputeOrdering(s, *p.mesh, seed).new_to_old();
            }
            return Give(std::move(v));
          },
          py::arg("spec"), py::arg("seed") = 1)
      .def(
          "permute",
          [](const PyMesh& p, py::array_t<int64_t, py::array::c_style | py::array::forcecast> perm,
             const std::string& triangle_order) {
            const Permutation q = PermutationOf(p, perm);
            const TriangleOrder order = ParseTriangleOrder(triangle_order);
            PyMesh out;
            LongWork work;
            out.mesh = std::make_shared<Mesh>(ApplyPermutation(*p.mesh, q, order));
            out.name = p.name;
            return out;
          },
          py::arg("perm"), py::arg("triangle_order") = "sorted")
      .def(
          "write",
          [](const PyMesh& p, const std::string& path) {
            LongWork work;
            PhaseProgress phase("writing " + path, PollingListener());
            return WriteMesh(*p.mesh, path);
          },
          py::arg("path"));

  m.def(
      "save_permutation",
      [](const PyMesh& p, py::array_t<int64_t, py::array::c_style | py::array::forcecast> perm,
         const std::string& path, const std::string& comment) {
        const Permutation q = PermutationOf(p, perm);
        WritePermutation(q.new_to_old(), path, comment);
      },
      py::arg("mesh"), py::arg("perm"), py::arg("path"), py::arg("comment") = "from Python",
      "Writes a permutation of the mesh's vertices (new id -> old id, checked) as a file: ordering "
      "spec reads it (one id per line), so compare() and analyze() can race it by name "
      "(orderings=['mine=file:PATH']).");
  m.def("_orderings", [] {
    py::list out;
    for (const OrderingInfo& o : Orderings()) {
      py::dict d;
      d["name"] = o.name;
      d["description"] = o.description;
      d["reference"] = o.reference;
      d["seeded"] = o.seeded;
      d["argument"] = o.argument == kArgument           ? "required"
                      : o.argument == kOptionalArgument ? "optional"
                                                        : "none";
      out.append(d);
    }
    return out;
  });
  m.def(
      "_smooth",
      [](const PyMesh& p, const std::string& mode, const std::string& quality, int max_iters,
         double tol, int threads, const std::string& kernel) {
        const KernelInfo& k = ParseKernel(kernel);
        SmoothOptions o;
        o.mode = ParseUpdateMode(mode);
        o.quality = ParseQualityMode(quality);
        if (max_iters < 1) throw UsageError("max_iters must be at least 1");
        if (!(tol == tol)) throw UsageError("tol must be a number");
        if (threads < 1 || threads > kMaxThreads)
          throw UsageError("threads must be 1.." + std::to_string(kMaxThreads));
        o.max_iters = max_iters, o.tol = tol, o.threads = threads;
        CheckKernelOptions(k, o);
        Mesh work = p.mesh->Clone();
        SmoothResult r;
        {
          LongWork long_work;
          r = RunKernel(k, work, o);
        }
        py::dict d = SweepDict(r);
        std::vector<double> xy(work.xy.begin(), work.xy.end());
        py::array points = Give(std::move(xy));
        d["points"] = points.attr("reshape")(-1, 2);
        return d;
      },
      py::arg("mesh"), py::arg("mode"), py::arg("quality"), py::arg("max_iters"), py::arg("tol"),
      py::arg("threads"), py::arg("kernel"));
  m.def("_kernels", [] {
    py::list out;
    for (const KernelInfo& k : Kernels()) {
      py::dict d;
      d["name"] = k.name;
      d["visits"] = VisitUnitName(k.unit);
      d["measure"] = k.measure;
      d["threads"] = k.threads;
      d["jacobi"] = k.jacobi;
      d["description"] = k.description;
      d["reference"] = k.reference;
      out.append(d);
    }
    return out;
  });
  m.def(
      "_trace",
      [](const PyMesh& p, const std::string& ordering, uint64_t seed, int iterations, int threads,
         const std::string& mode, const std::string& triangle_order, const std::string& kernel) {
        const OrderingSpec spec = ParseOrderingSpec(ordering);
        const KernelInfo& k = ParseKernel(kernel);
        if (iterations < 1 || iterations > kMaxStreamSweeps)
          throw UsageError("iterations must be 1.." + std::to_string(kMaxStreamSweeps));
        if (threads < 1 || threads > kMaxThreads)
          throw UsageError("threads must be 1.." + std::to_string(kMaxThreads));
        CheckStreamSweeps(iterations, threads);
        const SmoothOptions o = ExactSweeps(iterations, threads, ParseUpdateMode(mode));
        CheckKernelOptions(k, o);
        const TriangleOrder order = ParseTriangleOrder(triangle_order);
        auto* held = new Collect;
        py::capsule free(held, [](void* q) { delete static_cast<Collect*>(q); });
        {
          LongWork work;
          Mesh laid = ApplyPermutation(*p.mesh, ComputeOrdering(spec, *p.mesh, seed), order);
          StreamMesh(laid, o, p.name, spec.label, *held, &k);
        }
        return py::array_t<Access>(static_cast<py::ssize_t>(held->out.size()), held->out.data(),
                                   free);
      },
      py::arg("mesh"), py::arg("ordering"), py::arg("seed"), py::arg("iterations"),
      py::arg("threads"), py::arg("mode"), py::arg("triangle_order"), py::arg("kernel"));
}

}  // namespace meshreuse::python
