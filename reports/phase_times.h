// Where a long run's time went (issue 40: the report's critical path, measured): wall and CPU
// seconds per named phase, in the order first seen; a phase entered again adds up. CPU is the
// whole process's (every thread, and children it waited for) unless the caller measures its own.
// Phases from before the run (scripts/reproduce.sh's build and meshing) come from a small text
// file, one "NAME WALL CPU" per line ('#' comments), so the report's README and run.json hold the
// whole job's breakdown.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "reports/run_info.h"

namespace meshreuse {

// Every thread of this process (CLOCK_PROCESS_CPUTIME_ID) and its children that have ended (the
// figures' python).
double ProcessCpuSeconds();

class PhaseTimes {
 public:
  struct Phase {
    std::string name;
    double wall = 0, cpu = 0;
    std::string note;  // e.g. "ran beside the other configurations"
  };
  // Times from construction to destruction into `name` (wall, and this process's CPU); `note`
  // marks a phase inside another (not added into the total).
  class Scope {
   public:
    Scope(PhaseTimes* t, std::string name, std::string note = "");
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PhaseTimes* t_;
    std::string name_, note_;
    std::chrono::steady_clock::time_point w0_;
    double c0_;
  };
  Scope Time(const std::string& name, const std::string& note = "") {
    return Scope(this, name, note);
  }
  void Add(const std::string& name, double wall, double cpu, const std::string& note = "");
  const std::vector<Phase>& phases() const { return phases_; }
  // "NAME WALL CPU" lines (seconds, non-negative); InputError naming the file and line otherwise.
  void AddFile(const std::string& path);
  // [{"phase", "wall_s", "cpu_s", "note"}...]
  Json ToJson() const;
  // A Markdown table (phase, wall, CPU, CPU / wall, share of the total wall) and its total line;
  // a phase with a note (one of several that ran at once, inside another phase) is shown but not
  // added into the total.
  std::string Markdown() const;

 private:
  std::vector<Phase> phases_;
};

}  // namespace meshreuse
