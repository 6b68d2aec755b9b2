// The reuse job's analyzer options and the ranks' statistics as JSON; see reuse_job.h.
#include "reports/reuse_job.h"

namespace meshreuse {

ReuseOptions ReuseJob::Options(Granularity g) const {
  ReuseOptions o;
  o.granularity = g;
  o.line_bytes = line_bytes;
  o.exact = !sample || sample_error;
  o.sample = sample;
  o.shards = shards;
  o.watch_element = watch_element;
  o.watch_line = watch_line;
  o.profile = profile;
  return o;
}

Json RankStatsJson(const std::vector<RankStats>& ranks) {
  Json a = Json::array();
  for (const RankStats& r : ranks)
    a.push_back({{"rank", r.rank},
                 {"analyse_cpu_s", r.analyse_cpu},
                 {"stream_cpu_s", r.stream_cpu},
                 {"resolve_cpu_s", r.resolve_cpu},
                 {"reduce_cpu_s", r.reduce_cpu},
                 {"wall_s", r.wall},
                 {"records", r.records},
                 {"accesses", r.accesses},
                 {"distinct", r.distinct},
                 {"stack_ids_in", r.stack_ids_in},
                 {"stack_ids_sent", r.stack_ids_sent},
                 {"bytes_sent", r.bytes_sent},
                 {"peak_rss_bytes", r.peak_rss_bytes},
                 {"histogram_bytes", r.histogram_bytes},
                 {"dense_histogram_bytes", r.dense_histogram_bytes},
                 {"pairs", r.pairs},
                 {"pairs_added", r.pairs_added},
                 {"merge_cpu_s", r.merge_cpu}});
  return a;
}

}  // namespace meshreuse
