// table3: estimated misses per sweep and the inverse model's capacities (the paper's Table 3),
// from the validation runs (reports/validation.h: simulated, or counted where PAPI counts).
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportTable3(const ReportData& d) {
  ReportPart p;
  p.table = Table3(d.validation);
  p.note = "Misses per sweep over the traced sweeps (" + d.counters +
           "), and the capacity the inverse model gives for them. The traced sweeps start from "
           "empty caches, so the first sweep's cold misses are counted; the miss rates and "
           "reductions below use the last sweep. The paper measured whole runs with PAPI on "
           "Westmere-EX, whose prefetchers our simulator does not model.";
  return p;
}

}  // namespace meshreuse
