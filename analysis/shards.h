// Spatially hashed sampling of a reuse-distance stream: SHARDS (Waldspurger, Park, Garthwaite and
// Ahmad, FAST 2015), for traces too large to analyse exactly. An id is sampled when its hash
// (SplitMix64 of id ^ seed, the top 56 bits) is below a threshold T = R * 2^56: all accesses of a
// sampled id are kept, so reuse distances among sampled ids, divided by R, estimate the true ones.
//   - fixed rate: R given; each sample counts 1/R accesses; SHARDS_adj corrects the distance-0
//     count by the difference between the accesses expected at rate R (N) and the samples' weight
//     (the published bias fix).
//   - fixed size: at most s_max ids are tracked; when one more arrives, the id with the largest
//     hash is dropped and T lowered to its hash, so R falls as the trace goes on. A sample counts
//     1/R at its time (the same relative weights as SHARDS' rescaling of the histogram by
//     R_new/R_old), and the curve is normalised by the samples' total weight.
// The estimate is a weighted histogram over scaled distances (round(d / R)): miss ratio at any
// capacity, quantiles, mean. Memory: the exact analyzer over the sampled ids only.
// Small distances (exact_below = K > 0): scaling by 1/R puts every sampled distance below 1/R at
// 0 or 1/R, so the curve is coarsest where caches are small. With K, every access also goes
// through an exact LRU stack of depth K (bounded_stack.h: memory O(K), not O(ids)); distances
// below K are then counted exactly. A sampled access whose true distance is below K adds no
// weight (it is counted already), and one whose true distance is K or more lands at K at least:
// so the sample's tail holds only accesses truly beyond K, and no small distance leaks across K
// through the scaling (an earlier version let them: -15% at 4 K on a mesh-like trace). The tail
// (and the cold weight) is then scaled to carry exactly the accesses the exact counts leave. The
// miss ratio at every capacity up to K is exact. Serial streams only (not FromSampled).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "analysis/bounded_stack.h"
#include "analysis/reuse_histogram.h"
#include "analysis/stack_distance.h"

namespace meshreuse {

struct ShardsOptions {
  double rate = 0.01;  // fixed rate (used when s_max == 0), in (0, 1]
  uint64_t s_max = 0;  // fixed size: ids tracked at most (0: fixed rate)
  uint64_t seed = 1;
  bool adjust = true;        // SHARDS_adj (fixed rate only)
  uint32_t exact_below = 0;  // K: distances below K counted exactly (0: off)
  // Capacities (in the stream's ids) whose miss estimates get a sampling error bound (MissBound):
  // each sampled id keeps, per capacity, its accesses that miss there.
  std::vector<uint64_t> watch;
};

class Shards {
 public:
  explicit Shards(const ShardsOptions& o);
  void Access(uint64_t id) {
    ++accesses_;
    bool small = false;
    if (exact_) {
      const uint64_t d = exact_->Access(id);
      if (d != BoundedStackDistance::kFar) ++small_[d], small = true;
    }
    const uint64_t h = Hash(id);
    if (h >= threshold_) return;
    Sampled(id, h, small);
  }
  void Finish();  // applies SHARDS_adj; call once at the end
  // Whether `id` is sampled (fixed rate: the threshold never moves).
  bool Keeps(uint64_t id) const { return Hash(id) < threshold_; }
  // The estimate of a stream of `accesses` whose sampled ids' exact distances are `sampled`
  // (analysed elsewhere: chunks, ranks), bit for bit the one Access() would have built: at a
  // fixed rate every sample adds the same weight 1/R, so each sum is that weight added as many
  // times, whatever the order. Fixed rate only (std::invalid_argument otherwise).
  static Shards FromSampled(const ShardsOptions& o, uint64_t accesses,
                            const ReuseHistogram& sampled);

  uint64_t accesses() const { return accesses_; }
  uint64_t samples() const { return samples_; }
  double rate() const { return static_cast<double>(threshold_) * 0x1.0p-56; }  // the final R
  const ShardsOptions& options() const { return opt_; }
  double total_weight() const { return total_; }
  double cold_weight() const { return cold_; }
  double distinct_estimate() const { return distinct_; }
  const std::map<uint64_t, double>& weights() const { return weight_; }  // scaled d -> weight
  double MissRatio(uint64_t capacity) const;  // distances >= capacity, and cold, over total
  // The 95% sampling bound (half-width, in accesses) of the misses estimated at watch[i]
  // (accesses x MissRatio): from the spread of the sampled ids' own misses, as for any Poisson
  // sample of ids (Horvitz-Thompson at a fixed rate; a ratio estimator, linearised, where the
  // estimate is scaled to a known total: with exact_below, or at a fixed size). 0 below
  // exact_below (exact); NaN without per-id counts (FromSampled). What it leaves out: the error
  // of scaling each distance by 1/R, which --sample-error measures against the exact analysis.
  // Call after Finish.
  double MissBound(size_t i) const;
  uint64_t sampled_ids() const { return sampled_ids_; }  // ids the sample held (first touches)
  double Mean() const;                                   // of the finite scaled distances
  uint64_t Quantile(double x) const;                     // as ReuseHistogram::Quantile, weighted
  size_t MemoryBytes() const {
    return sd_.MemoryBytes() + heap_.size() * 16 + weight_.size() * 48 +
           (exact_ ? exact_->depth() * size_t{80} : 0);
  }
  // With exact_below: the accesses at each distance below K, counted exactly.
  const std::vector<uint64_t>& exact_small() const { return small_; }

 private:
  uint64_t Hash(uint64_t id) const {
    uint64_t x = id ^ seed_mix_;
    x ^= x >> 30;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 27;
    x *= 0x94D049BB133111EBull;
    return (x ^ (x >> 31)) >> 8;
  }
  // `small`: the access's distance is below exact_below, counted exactly already.
  void Sampled(uint64_t id, uint64_t h, bool small = false);

  ShardsOptions opt_;
  uint64_t seed_mix_;
  uint64_t threshold_;
  StackDistance sd_;
  std::priority_queue<std::pair<uint64_t, uint64_t>> heap_;  // (hash, id) of tracked ids
  std::map<uint64_t, double> weight_;
  double total_ = 0, cold_ = 0, distinct_ = 0;
  uint64_t accesses_ = 0, samples_ = 0;
  bool finished_ = false;
  std::unique_ptr<BoundedStackDistance> exact_;  // with exact_below
  std::vector<uint64_t> small_;
  uint64_t sampled_ids_ = 0;
  // Per sampled id (index from id_slot_), watch.size() + 1 counters: its accesses missing at
  // each watched capacity, then those the tail holds (all its samples without exact_below).
  std::unordered_map<uint64_t, uint32_t> id_slot_;
  std::vector<uint32_t> id_counts_;
  bool per_id_ = false;
};

// The exact miss ratio at every capacity 1..max distance + 1 against the estimate: the mean
// absolute difference (SHARDS' error measure).
double MrcMeanAbsoluteError(const ReuseHistogram& exact, const Shards& estimate);

}  // namespace meshreuse
