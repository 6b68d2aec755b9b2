// Laplacian smoothing of one rank's part (rank_part.h) with the ghost exchanges of
// ../shared/scale-out.md 3b, behind a transport that only moves bytes (MPI in cli/mpi_main.cc,
// threads in core/halo_threads.h), so this library stays MPI-free. Three modes:
//   ordered (default): non-cut vertices in local order; then, once every neighbour of a lower
//     colour has sent its new cut values, the cut vertices in local order; the new cut values go
//     to every neighbour; the higher colours' values are received before the sweep ends. Same-
//     colour parts never touch and non-cut vertices read owned values only, so one sweep is bit for
//     bit the serial Gauss-Seidel sweep along pi = (every rank's non-cut vertices) ++ (cut vertices
//     of colour 0) ++ (colour 1) ++ ... (GatheredVisitOrder): each vertex reads the new value of
//     a neighbour before it in pi and the old value of one after it, summed in increasing global id
//     (the serial mesh's row order). `meshreuse smooth --visit-order` runs that serial sweep.
//     That is the default cut placement (rank_part.h, kLast). With kFirst a rank waits for the
//     lower colours, moves its cut vertices, sends them and moves its non-cut ones while they
//     travel: pi = (cut vertices of colour 0) ++ (colour 1) ++ ... ++ (every rank's non-cut
//     vertices), exact because a cut vertex reads its own non-cut neighbours' old values and a
//     non-cut vertex reads owned values only. With kInterleaved a rank waits for the lower colours,
//     then sweeps everything in its ordering: pi = (colour 0's parts whole) ++ (colour 1's) ++ ...
//     (a colour's sweep waits for the whole sweep of the ones below: the placement's cost).
//   jacobi: every movable vertex from the previous sweep's values, then one exchange: bit for bit
//     the serial Jacobi sweep.
//   hybrid: Gauss-Seidel inside the part reading ghosts from the previous sweep, one exchange per
//     sweep. Equal to no serial order: for timing studies only.
// A move is the serial smoother's (MoveToAverage, smoother.h) operation for operation. The global
// quality Q = sum_t w_t q_t is summed over owned triangles in exact fixed point (fixed_sum.h) and
// combined across ranks, so Q, each sweep's improvement and the stop decision are identical for
// every number of ranks (the serial smoother sums in floating point: its Q differs in the last
// bits, its moves do not). Stop rule as the serial one: a sweep improving Q by less than `tol` is
// the last; at most `max_iters` sweeps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/fixed_sum.h"
#include "core/mesh.h"
#include "core/rank_part.h"

namespace meshreuse {

// What a rank needs from the others. Messages between two ranks arrive in the order sent.
class HaloTransport {
 public:
  virtual ~HaloTransport() = default;
  virtual int32_t rank() const = 0;
  virtual int32_t size() const = 0;
  // May return before delivery: `data` stays untouched until the next Flush().
  virtual void Send(int32_t to, const double* data, size_t n) = 0;
  virtual void Recv(int32_t from, double* data, size_t n) = 0;  // blocks until it arrives
  virtual void Flush() = 0;                                     // every Send delivered
  virtual FixedSum SumAll(const FixedSum& mine) = 0;            // the sum over all ranks
  // Rank 0 gets every rank's bytes (by rank); the others an empty vector.
  virtual std::vector<std::string> Gather(const std::string& mine) = 0;
  virtual std::vector<std::string> AllGather(const std::string& mine) = 0;  // every rank, all
};

enum class HaloMode { kOrdered, kJacobi, kHybrid };
HaloMode ParseHaloMode(const std::string& s);  // ordered | jacobi | hybrid; UsageError
const char* HaloModeName(HaloMode m);

struct HaloOptions {
  int max_iters = 100;
  double tol = 5e-6;
  HaloMode mode = HaloMode::kOrdered;
};

struct HaloSweep {
  int sweep = 0;            // 1-based
  double quality = 0;       // Q after the sweep (exact sum, rounded once)
  double improvement = 0;   // Q - previous Q (exact difference, rounded once)
  double seconds = 0;       // wall time of the sweep on this rank, quality reduction included
  double cpu_seconds = 0;   // this rank's thread CPU time moving vertices and packing
  double wait_seconds = 0;  // wall time blocked in Recv
};

struct HaloResult {
  std::vector<HaloSweep> sweeps;
  FixedSum quality_before, quality_after;
  bool converged = false;
  uint64_t messages = 0, values_sent = 0;  // doubles sent, all sweeps
};

// Q over the part's owned triangles (its share of the global quality).
FixedSum PartQuality(const RankPart& p);
// The same sum over the whole mesh, serially: what the ranks' shares add up to.
FixedSum FixedGlobalQuality(const Mesh& m);

// Smooths the part in place; every rank of the transport calls it with the same options.
// `on_sweep` runs after each sweep (after the reduction: the same values on every rank).
HaloResult SmoothRankPart(RankPart& p, const HaloOptions& opt, HaloTransport& tx,
                          const std::function<void(const HaloSweep&)>& on_sweep = {});

}  // namespace meshreuse
