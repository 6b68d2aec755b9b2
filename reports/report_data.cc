// ReportData's look-ups and the builders' shared helpers; see report_data.h.
#include "reports/report_data.h"

#include <algorithm>
#include <cmath>

#include "reports/inputs.h"

namespace meshreuse {

const MachineRun* ReportData::Machine(const std::string& mesh, const std::string& ordering,
                                      const std::string& placement, int threads,
                                      bool prefetch) const {
  return FindMachineRun(machine, mesh, ordering, placement, threads, prefetch);
}

const CompareRow* ReportData::Time(const std::string& mesh, const std::string& ordering,
                                   int threads) const {
  for (const CompareRow& r : timing)
    if (r.ordering == ordering && r.threads == threads && MeshShortName(r.mesh) == mesh) return &r;
  return nullptr;
}

const ReportMesh* ReportData::Mesh(const std::string& name) const {
  for (const ReportMesh& m : meshes)
    if (m.name == name) return &m;
  return nullptr;
}

bool ReportData::Has(const std::string& ordering) const {
  return std::find(orderings.begin(), orderings.end(), ordering) != orderings.end();
}

namespace report {

std::string Num(double v, int decimals) {
  if (!std::isfinite(v)) return "";
  std::string s = Fixed(v, decimals);
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);  // no "-0.0"
  return s;
}

double Ratio(double a, double b) { return b > 0 ? a / b : NAN; }

double Mean(const std::vector<double>& v) {
  double s = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) s += x, ++n;
  return n ? s / n : NAN;
}

double LastSweepMisses(const OrderingValidation& v, size_t level, LevelStats* sum,
                       uint64_t* line_accesses) {
  *sum = LevelStats();
  *line_accesses = 0;
  if (!v.sweeps.empty()) {
    const auto& last = v.sweeps.back();
    for (const auto& th : last) {
      *line_accesses += th.empty() ? 0 : th[0].accesses;
      *sum += th[level];
    }
  }
  const LevelValidation& l = v.levels[level];
  return l.measured ? l.counter / v.iterations : static_cast<double>(sum->misses);
}

std::string VerdictCell(const Spread& s, bool gain) {
  if (!std::isfinite(s.median)) return "";
  return VerdictName(gain ? GainVerdict(s) : SpeedupVerdict(s));
}

int DistanceBin(uint64_t d) {
  if (d == 0) return 0;
  return 1 +
         static_cast<int>(std::floor(std::log2(static_cast<double>(d)) * kDistanceBinsPerOctave));
}

uint64_t DistanceBinLo(int b) {
  return b == 0 ? 0
                : static_cast<uint64_t>(std::ceil(std::exp2((b - 1.0) / kDistanceBinsPerOctave)));
}

}  // namespace report

}  // namespace meshreuse
