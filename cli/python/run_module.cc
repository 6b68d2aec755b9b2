// The runners for Python (module.h): analyze, simulate and compare configured by the commands' own
// option parsing (cli/configs.h: the package turns keywords into options), over files, a mesh
// already read or built (StreamSource::loaded) or ids in memory (StreamSource::ids: a numpy array
// read where it lies, streamed exactly as a u64 trace file of the same values), run with the GIL
// released and Ctrl-C checked at progress points. What comes back is what the command prints and
// writes (RunOutput: every table, cell for cell as its CSV, the lines under it, run.json's fields),
// and for analyze each exact stream's histogram as numpy arrays, straight from the analysis.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/configs.h"
#include "cli/python/module.h"
#include "core/error.h"
#include "reports/chunks/summarize_chunk.h"

namespace meshreuse::python {

namespace {

// A column of cells as Python holds it: a numpy array of int64 when every cell is a whole number
// that fits, of float64 when every cell is a number or empty (NaN), else a list of str (None for
// an empty cell); whole numbers beyond 64 bits (exact sums) as a list of Python ints.
py::object Column(const std::vector<std::string>& cells) {
  const size_t n = cells.size();
  bool ints = true, big = false, floats = true, any = false;
  std::vector<int64_t> iv(n);
  std::vector<double> fv(n);
  for (size_t r = 0; r < n; ++r) {
    const std::string& x = cells[r];
    if (x.empty()) {
      ints = false, fv[r] = std::nan("");
      continue;
    }
    any = true;
    const char* b = x.data();
    const char* e = b + x.size();
    if (ints) {
      const auto res = std::from_chars(b, e, iv[r]);
      if (res.ec == std::errc::result_out_of_range &&
          x.find_first_not_of("-0123456789") == std::string::npos)
        big = true;
      else if (res.ec != std::errc() || res.ptr != e)
        ints = false;
    }
    if (floats) {
      char* end = nullptr;
      fv[r] = std::strtod(b, &end);
      if (end != e) floats = false;
    }
  }
  if (!any) return py::list(py::cast(std::vector<py::object>(n, py::none())));
  if (ints && big) {
    py::list l;
    for (const std::string& x : cells) l.append(py::int_(py::str(x)));
    return std::move(l);
  }
  if (ints) return py::array_t<int64_t>(static_cast<py::ssize_t>(n), iv.data());
  if (floats) return py::array_t<double>(static_cast<py::ssize_t>(n), fv.data());
  py::list l;
  for (const std::string& x : cells) l.append(x.empty() ? py::object(py::none()) : py::str(x));
  return std::move(l);
}

// A table as Python holds it: column name -> Column, in the table's order.
py::dict TableToPython(const Table& t) {
  const std::vector<std::string>& header = t.Header();
  std::vector<std::vector<std::string>> cells(header.size());
  for (size_t r = 0; r < t.Rows(); ++r) {
    std::vector<std::string> row = t.Row(r);
    for (size_t c = 0; c < header.size(); ++c) cells[c].push_back(std::move(row[c]));
  }
  py::dict cols;
  for (size_t c = 0; c < header.size(); ++c) cols[py::str(header[c])] = Column(cells[c]);
  return cols;
}

// What a runner produced, held for Python: its tables are converted when asked for (a histogram
// or a miss-ratio curve may have a row per distance, which the command builds only when it writes
// it), analyze's miss-ratio curve computed then.
struct PyRun {
  RunOutput out;
  std::shared_ptr<AnalyzeResult> analysis;
  std::map<std::string, std::shared_ptr<const Table>> more;  // computed on demand

  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    for (const RunOutput::TableFile& f : out.tables) names.push_back(f.name);
    if (analysis) names.push_back("mrc");
    return names;
  }
  py::dict Get(const std::string& name) {
    for (const RunOutput::TableFile& f : out.tables)
      if (f.name == name) return TableToPython(*f.table);
    if (analysis && name == "mrc") {
      auto& t = more[name];
      if (!t) {
        LongWork work;
        t = std::make_shared<const Table>(MrcTable(*analysis));
      }
      return TableToPython(*t);
    }
    throw py::key_error(name);
  }
  std::string Text() const {
    std::string text;  // what the command prints for people
    for (const auto& item : out.text)
      text += std::holds_alternative<std::string>(item)
                  ? std::get<std::string>(item) + "\n"
                  : std::get<RunOutput::TablePtr>(item)->Aligned();
    return text;
  }
};

// A Log for the runners: progress lines on stderr when asked, warnings always (as the command
// line's), Ctrl-C looked for at every line.
Log PythonLog(bool progress) {
  Log log;
  log.progress = [progress](const std::string& s) {
    if (progress) std::fprintf(stderr, "meshreuse: %s\n", s.c_str());
    PollSignals();
  };
  log.warn = [](const std::string& s) { Warn(s); };
  return log;
}

// Points a stream source at what `memory` holds: a Mesh (its name must be inputs[0]) or ids (a
// C-contiguous uint64 array, held by the caller for the run).
cli::InMemory Memory(const py::object& memory) {
  if (memory.is_none()) return {};
  if (py::isinstance<PyMesh>(memory)) {
    const Mesh* m = memory.cast<const PyMesh&>().mesh.get();
    return [m](StreamSource& s) { s.loaded = m; };
  }
  // The caller's own array, not a converted copy that would die before the run (the package
  // hands C-contiguous uint64 ids).
  using Ids = py::array_t<uint64_t, py::array::c_style>;
  if (!Ids::check_(memory) || memory.cast<py::array>().ndim() != 1)
    throw py::type_error("ids must be a one-dimensional C-contiguous uint64 array");
  const Ids ids = py::reinterpret_borrow<Ids>(memory);
  const uint64_t* data = ids.data();
  const uint64_t n = static_cast<uint64_t>(ids.size());
  return [data, n](StreamSource& s) {
    s.ids = data, s.ids_count = n;
    s.poll = [] { PollSignals(); };
  };
}

// Every exact stream of the analysis: its key, counts and histogram (distances with a count, in
// increasing order, and the counts) as numpy arrays.
py::list Streams(const AnalyzeResult& r) {
  py::list out;
  for (const auto& run : r.runs)
    for (int t = 0; t < run->threads(); ++t)
      for (Granularity g : {Granularity::kElement, Granularity::kLine}) {
        const StreamAnalysis* s = run->stream(t, g);
        if (!s || !s->exact) continue;
        std::vector<uint64_t> dist, count;
        s->hist.ForEach([&](uint64_t d, uint64_t c) { dist.push_back(d), count.push_back(c); });
        py::dict d;
        d["input"] = run->info().input;
        d["ordering"] = run->info().ordering;
        d["thread"] = t;
        d["granularity"] = GranularityName(g);
        d["accesses"] = s->hist.accesses();
        d["cold"] = s->hist.cold();
        d["sum"] = py::int_(py::str(ToDecimal(s->hist.sum())));
        d["max"] = s->hist.max();
        d["distances"] = py::array_t<uint64_t>(static_cast<py::ssize_t>(dist.size()), dist.data());
        d["counts"] = py::array_t<uint64_t>(static_cast<py::ssize_t>(count.size()), count.data());
        out.append(d);
      }
  return out;
}

py::object Analyze(const std::vector<std::string>& args, const py::object& memory, bool profile,
                   bool progress) {
  AnalyzeConfig cfg = cli::AnalyzeConfigFromArgs(args, Memory(memory));
  cfg.profile = profile;
  const Log log = PythonLog(progress);
  if (cfg.chunk) {
    if (cfg.summary_out.empty()) throw UsageError("chunk needs summary_out (the file to write)");
    LongWork work;
    RunChunk(cfg, cfg.chunk->first, cfg.chunk->second, cfg.summary_out, log);
    return py::none();
  }
  AnalyzeResult r;
  {
    LongWork work;
    r = RunAnalyze(cfg, log);
  }
  if (r.sampling) {  // merged summaries of a sampled analysis: their tables (as the command)
    cfg.sample = true;
    cfg.shards = *r.sampling;
    cfg.sample_error = r.sampling_with_exact;
  }
  for (const std::string& w : SampleWarnings(r, cfg)) Warn(w);
  auto run = std::make_shared<PyRun>();
  run->out = AnalyzeOutput(r, cfg);
  run->analysis = std::make_shared<AnalyzeResult>(std::move(r));
  py::dict d;
  d["run"] = run;
  d["streams"] = Streams(*run->analysis);
  py::list q;
  for (double x : cfg.quantiles) q.append(x);
  d["quantiles"] = q;
  return std::move(d);
}

std::shared_ptr<PyRun> Simulate(const std::vector<std::string>& args, const py::object& memory,
                                bool per_sweep, bool progress) {
  const SimulateConfig cfg = cli::SimulateConfigFromArgs(args, Memory(memory));
  const Log log = PythonLog(progress);
  auto run = std::make_shared<PyRun>();
  LongWork work;
  if (!cfg.machine.empty())
    run->out = MachineOutput(RunMachineSimulate(cfg, log), cfg);
  else
    run->out = SimulateOutput(RunSimulate(cfg, log), cfg, per_sweep);
  return run;
}

std::shared_ptr<PyRun> Compare(const std::vector<std::string>& args, bool progress) {
  const CompareConfig cfg = cli::CompareConfigFromArgs(args);
  const Log log = PythonLog(progress);
  CompareResult r;
  {
    LongWork work;
    r = RunCompare(cfg, log.progress, log.warn);
  }
  for (const std::string& why : r.noise.Reasons()) Warn("timings taken on a busy machine: " + why);
  auto run = std::make_shared<PyRun>();
  run->out = CompareOutput(r, cfg);
  return run;
}

}  // namespace

void BindRunners(py::module_& m) {
  py::class_<PyRun, std::shared_ptr<PyRun>>(m, "_Run")
      .def("names", &PyRun::Names)
      .def("table", &PyRun::Get)
      .def("csv",
           [](const PyRun& r) -> py::object {
             if (!r.out.csv) return py::none();
             return TableToPython(*r.out.csv);
           })
      .def("text", &PyRun::Text)
      .def("configuration", [](const PyRun& r) { return r.out.configuration.dump(); })
      .def("extra",
           [](const PyRun& r) { return r.out.extra.is_null() ? "{}" : r.out.extra.dump(); });
  m.def("_analyze", &Analyze, py::arg("args"), py::arg("memory"), py::arg("profile"),
        py::arg("progress"));
  m.def("_simulate", &Simulate, py::arg("args"), py::arg("memory"), py::arg("per_sweep"),
        py::arg("progress"));
  m.def("_compare", &Compare, py::arg("args"), py::arg("progress"));
}

}  // namespace meshreuse::python
