// Shards; see shards.h.
#include "analysis/shards.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

namespace meshreuse {

Shards::Shards(const ShardsOptions& o)
    : opt_(o), seed_mix_(o.seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull), sd_(0) {
  if (o.s_max == 0 && !(o.rate > 0 && o.rate <= 1))
    throw std::invalid_argument("the sampling rate must be in (0, 1]");
  threshold_ = o.s_max ? uint64_t{1} << 56 : static_cast<uint64_t>(std::ldexp(o.rate, 56));
  if (threshold_ == 0) threshold_ = 1;
  if (o.exact_below) {
    exact_ = std::make_unique<BoundedStackDistance>(o.exact_below);
    small_.assign(o.exact_below, 0);
  }
  per_id_ = !o.watch.empty();
}

void Shards::Sampled(uint64_t id, uint64_t h, bool small) {
  ++samples_;
  const double r = rate();
  const uint64_t d = sd_.Access(id);
  const double w = 1.0 / r;
  total_ += w;
  if (d == StackDistance::kCold) ++sampled_ids_;
  const uint64_t scaled =
      d == StackDistance::kCold
          ? UINT64_MAX
          : std::max<uint64_t>(opt_.exact_below,
                               static_cast<uint64_t>(std::llround(static_cast<double>(d) / r)));
  if (!opt_.watch.empty()) {
    const size_t n = opt_.watch.size() + 1;
    const auto [it, fresh] = id_slot_.try_emplace(id, static_cast<uint32_t>(id_counts_.size() / n));
    if (fresh) id_counts_.resize(id_counts_.size() + n, 0);
    uint32_t* c = &id_counts_[static_cast<size_t>(it->second) * n];
    if (!small) {
      for (size_t i = 0; i < opt_.watch.size(); ++i) c[i] += scaled >= opt_.watch[i];
      ++c[n - 1];
    }
  }
  if (d == StackDistance::kCold) {
    cold_ += w;
    distinct_ += w;
    if (opt_.s_max) {
      heap_.emplace(h, id);
      if (heap_.size() > opt_.s_max) {  // drop the largest hash; the threshold falls to it
        threshold_ = heap_.top().first;
        while (!heap_.empty() && heap_.top().first >= threshold_) {
          sd_.Remove(heap_.top().second);
          heap_.pop();
        }
      }
    }
    return;
  }
  if (!small) weight_[scaled] += w;  // a small one is in the exact counts
}

Shards Shards::FromSampled(const ShardsOptions& o, uint64_t accesses,
                           const ReuseHistogram& sampled) {
  if (o.s_max) throw std::invalid_argument("Shards::FromSampled: fixed rate only");
  if (o.exact_below)
    throw std::invalid_argument("Shards::FromSampled: exact small distances need the whole stream");
  Shards s(o);
  s.accesses_ = accesses;
  s.samples_ = sampled.accesses();
  s.sampled_ids_ = sampled.cold();  // each sampled id's first access is its one cold one
  const double w = 1.0 / s.rate();
  for (uint64_t k = 0; k < s.samples_; ++k) s.total_ += w;
  for (uint64_t k = 0; k < sampled.cold(); ++k) s.cold_ += w, s.distinct_ += w;
  sampled.ForEach([&](uint64_t d, uint64_t n) {
    double& bin = s.weight_[static_cast<uint64_t>(std::llround(static_cast<double>(d) / s.rate()))];
    for (uint64_t k = 0; k < n; ++k) bin += w;
  });
  return s;
}

void Shards::Finish() {
  if (finished_) return;
  finished_ = true;
  if (!opt_.s_max && opt_.adjust) {
    // SHARDS_adj: the expected weight is the access count; the shortfall (or excess) of the
    // samples goes to the smallest distance.
    const double diff = static_cast<double>(accesses_) - total_;
    weight_[0] += diff;
    total_ += diff;
  }
  if (!exact_) return;
  // Below K the exact counts; the tail (every weight is at K or beyond: see Sampled) and the cold
  // weight scaled to carry the accesses the exact counts leave.
  const uint64_t k = opt_.exact_below;
  uint64_t small = 0;
  for (uint64_t c : small_) small += c;
  weight_.erase(weight_.begin(), weight_.lower_bound(k));  // SHARDS_adj's distance 0
  double rest = cold_;
  for (const auto& kv : weight_) rest += kv.second;
  const double target = static_cast<double>(accesses_ - small);
  if (rest > 0) {
    const double f = target / rest;
    for (auto& kv : weight_) kv.second *= f;
    cold_ *= f;
  } else if (target > 0) {
    weight_[k] += target;  // known to lie at K or beyond; the sample saw none
  }
  for (uint64_t d = 0; d < k; ++d)
    if (small_[d]) weight_[d] = static_cast<double>(small_[d]);
  total_ = static_cast<double>(accesses_);
  exact_.reset();  // its memory is not needed any more
}

double Shards::MissBound(size_t i) const {
  if (!per_id_ || i >= opt_.watch.size()) return NAN;
  if (opt_.watch[i] < opt_.exact_below) return 0.0;  // counted exactly
  const double r = rate();
  const size_t n = opt_.watch.size() + 1;
  double var = 0;
  if (!opt_.s_max && !opt_.exact_below) {
    // A Horvitz-Thompson total: the misses are the sampled ids' own, each counted 1/R times.
    for (size_t k = 0; k < id_counts_.size(); k += n) {
      const double y = id_counts_[k + i];
      var += (1 - r) / (r * r) * y * y;
    }
  } else {
    // A ratio, the tail's share of the accesses it carries (all of them, or those the exact
    // counts leave): A x sum(y) / sum(z), linearised. At a fixed size R is the final rate (it fell
    // during the run, so the bound is approximate).
    double y = 0, z = 0;
    for (size_t k = 0; k < id_counts_.size(); k += n)
      y += id_counts_[k + i], z += id_counts_[k + n - 1];
    if (z <= 0) return 0.0;
    const double ratio = y / z;
    for (size_t k = 0; k < id_counts_.size(); k += n) {
      const double e = id_counts_[k + i] - ratio * id_counts_[k + n - 1];
      var += (1 - r) * e * e;
    }
    uint64_t small = 0;
    for (uint64_t c : small_) small += c;
    const double a = static_cast<double>(accesses_ - small);
    var *= a * a / (z * z);
  }
  return 1.959964 * std::sqrt(var);
}

double Shards::MissRatio(uint64_t capacity) const {
  if (total_ <= 0) return NAN;
  double miss = cold_;
  for (auto it = weight_.lower_bound(capacity); it != weight_.end(); ++it) miss += it->second;
  return std::min(1.0, std::max(0.0, miss / total_));
}

double Shards::Mean() const {
  double s = 0, w = 0;
  for (const auto& [d, x] : weight_) s += static_cast<double>(d) * x, w += x;
  return w > 0 ? s / w : NAN;
}

uint64_t Shards::Quantile(double x) const {
  if (!(x >= 0.0 && x <= 1.0)) throw std::invalid_argument("a quantile must be between 0 and 1");
  double finite = 0;
  for (const auto& kv : weight_) finite += kv.second;
  if (weight_.empty() || finite <= 0) throw std::domain_error("no finite reuse distances");
  double cum = 0;
  for (const auto& [d, w] : weight_) {
    cum += w;
    if (cum >= x * finite * (1 - 1e-12)) return d;
  }
  return weight_.rbegin()->first;
}

double MrcMeanAbsoluteError(const ReuseHistogram& exact, const Shards& est) {
  const uint64_t top = exact.max() + 1;
  if (exact.accesses() == 0) return NAN;
  // Both curves walked once from capacity 1 upwards: miss(c) = cold + count of distances >= c.
  const std::vector<std::pair<uint64_t, uint64_t>> counts = exact.Pairs();  // increasing d
  auto next = counts.begin();
  double exact_miss = static_cast<double>(exact.accesses());  // capacity 0: every access misses
  double est_miss = est.total_weight();
  auto it = est.weights().begin();
  double sum = 0;
  for (uint64_t c = 1; c <= top; ++c) {
    if (next != counts.end() && next->first == c - 1)
      exact_miss -= static_cast<double>(next++->second);
    while (it != est.weights().end() && it->first < c) est_miss -= it->second, ++it;
    sum += std::fabs(exact_miss / static_cast<double>(exact.accesses()) -
                     std::min(1.0, std::max(0.0, est_miss / est.total_weight())));
  }
  return sum / static_cast<double>(top);
}

}  // namespace meshreuse
