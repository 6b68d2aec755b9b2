// TraceAnalysis and the small parsers; see trace_analysis.h.
#include "analysis/trace_analysis.h"

#include <sys/stat.h>

#include <stdexcept>

namespace meshreuse {

Granularity ParseGranularity(const std::string& s) {
  if (s == "element") return Granularity::kElement;
  if (s == "line") return Granularity::kLine;
  if (s == "both") return Granularity::kBoth;
  throw std::invalid_argument("unknown granularity '" + s + "' (element, line or both)");
}

const char* GranularityName(Granularity g) {
  return g == Granularity::kElement ? "element" : g == Granularity::kLine ? "line" : "both";
}

ExternalFormat ParseExternalFormat(const std::string& s) {
  if (s == "text") return ExternalFormat::kText;
  if (s == "u32") return ExternalFormat::kU32;
  if (s == "u64") return ExternalFormat::kU64;
  throw std::invalid_argument("unknown trace format '" + s + "' (text, u32 or u64)");
}

uint64_t ExternalTraceLength(const std::string& path, ExternalFormat fmt) {
  if (fmt == ExternalFormat::kText || path == "-") return 0;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  return static_cast<uint64_t>(st.st_size) / (fmt == ExternalFormat::kU32 ? 4 : 8);
}

TraceAnalysis::TraceAnalysis(const TraceAnalysisOptions& o) : opt_(o) {
  if (o.threads < 1 || o.threads > 256) throw std::invalid_argument("threads must be 1..256");
  if (o.line_bytes == 0 || (o.line_bytes & (o.line_bytes - 1)))
    throw std::invalid_argument("the line size must be a power of two");
  line_shift_ = __builtin_ctz(o.line_bytes);
  for (int t = 0; t < o.threads; ++t) {
    const bool prof =
        static_cast<size_t>(t) < o.iteration_lengths.size() && !o.iteration_lengths[t].empty();
    const bool line_prof = static_cast<size_t>(t) < o.line_iteration_lengths.size() &&
                           !o.line_iteration_lengths[t].empty();
    std::unique_ptr<StreamAnalysis> e, l;
    if (static_cast<int>(o.granularity) & static_cast<int>(Granularity::kElement)) {
      e = std::make_unique<StreamAnalysis>(o.dense_elements);
      if (prof) e->profile = ReuseProfile(o.iteration_lengths[t], o.profile_steps);
    }
    if (static_cast<int>(o.granularity) & static_cast<int>(Granularity::kLine)) {
      l = std::make_unique<StreamAnalysis>(0);
      if (line_prof) l->profile = ReuseProfile(o.line_iteration_lengths[t], o.profile_steps);
    }
    element_.push_back(std::move(e));
    line_.push_back(std::move(l));
  }
}

}  // namespace meshreuse
