// Phase times; see phase_times.h.
#include "reports/phase_times.h"

#include <sys/resource.h>
#include <time.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "core/error.h"
#include "core/table.h"
#include "core/text_file.h"

namespace meshreuse {

double ProcessCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  rusage children{};
  getrusage(RUSAGE_CHILDREN, &children);
  auto secs = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec) +
         secs(children.ru_utime) + secs(children.ru_stime);
}

PhaseTimes::Scope::Scope(PhaseTimes* t, std::string name, std::string note)
    : t_(t),
      name_(std::move(name)),
      note_(std::move(note)),
      w0_(std::chrono::steady_clock::now()),
      c0_(ProcessCpuSeconds()) {
  t_->Add(name_, 0, 0, note_);  // listed when it starts: before the phases that run inside it
}

PhaseTimes::Scope::~Scope() {
  t_->Add(name_, std::chrono::duration<double>(std::chrono::steady_clock::now() - w0_).count(),
          ProcessCpuSeconds() - c0_, note_);
}

void PhaseTimes::Add(const std::string& name, double wall, double cpu, const std::string& note) {
  for (Phase& p : phases_)
    if (p.name == name) {
      p.wall += wall, p.cpu += cpu;
      if (p.note.empty()) p.note = note;
      return;
    }
  phases_.push_back({name, wall, cpu, note});
}

void PhaseTimes::AddFile(const std::string& path) {
  TextFile f(path);
  for (std::string_view line; f.NextDataLine(&line);) {
    std::string_view tok[4];
    if (Tokens(line).Split(tok, 4) != 3) f.Fail("expected NAME WALL_SECONDS CPU_SECONDS");
    const double wall = f.ParseDouble(tok[1], "wall seconds");
    const double cpu = f.ParseDouble(tok[2], "CPU seconds");
    if (!(wall >= 0 && cpu >= 0 && std::isfinite(wall) && std::isfinite(cpu)))
      f.Fail("seconds must be finite and not negative");
    Add(std::string(tok[0]), wall, cpu);
  }
}

Json PhaseTimes::ToJson() const {
  Json a = Json::array();
  for (const Phase& p : phases_) {
    Json j{{"phase", p.name}, {"wall_s", p.wall}, {"cpu_s", p.cpu}};
    if (!p.note.empty()) j["note"] = p.note;
    a.push_back(std::move(j));
  }
  return a;
}

std::string PhaseTimes::Markdown() const {
  double total = 0, cpu = 0;
  for (const Phase& p : phases_)
    if (p.note.empty()) total += p.wall, cpu += p.cpu;
  auto num = [](double x, const char* fmt) {
    char b[64];
    std::snprintf(b, sizeof b, fmt, x);
    return std::string(b);
  };
  std::string s =
      "| phase | wall | CPU | CPU / wall | share of the wall |\n|---|---|---|---|---|\n";
  for (const Phase& p : phases_) {
    s += "| " + p.name + (p.note.empty() ? "" : " (" + p.note + ")") + " | " +
         num(p.wall, "%.1f s") + " | " + num(p.cpu, "%.1f s") + " | " +
         (p.wall > 0 ? num(p.cpu / p.wall, "%.2f") : std::string("")) + " | " +
         (p.note.empty() && total > 0 ? num(100 * p.wall / total, "%.0f%%") : std::string("")) +
         " |\n";
  }
  s += "| **total** | **" + num(total, "%.1f s") + "** (" + Duration(total) + ") | " +
       num(cpu, "%.1f s") + " | " + (total > 0 ? num(cpu / total, "%.2f") : std::string("")) +
       " | 100% |\n";
  return s;
}

}  // namespace meshreuse
