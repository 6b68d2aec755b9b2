// PtScotchParts (mpi_ptscotch.h): SCOTCH_dgraphPart on the mesh's vertex graph, each rank its range
// of rows, then one all-gather of the parts.
#include "cli/mpi_ptscotch.h"

#include <mpi.h>
#include <ptscotch.h>
#include <scotch.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/rank_neighbourhood.h"

namespace meshreuse::cli {

std::vector<int32_t> PtScotchParts(const Mesh& m, int32_t parts, uint64_t seed) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (parts != size) throw std::invalid_argument("PtScotchParts: one part per rank of the job");
  const int64_t n = m.NumVertices();
  const int64_t lo = RangeFirst(rank, n, parts), hi = RangeFirst(rank + 1, n, parts);
  // This rank's rows of the vertex graph, global ids (v2v rows hold no self-loop).
  std::vector<SCOTCH_Num> vert(static_cast<size_t>(hi - lo + 1)), edge;
  edge.reserve(static_cast<size_t>(m.v2v.off[hi] - m.v2v.off[lo]));
  for (int64_t v = lo; v < hi; ++v) {
    for (const int32_t* q = m.v2v.RowBegin(static_cast<int32_t>(v));
         q != m.v2v.RowEnd(static_cast<int32_t>(v)); ++q)
      edge.push_back(*q);
    vert[v - lo + 1] = static_cast<SCOTCH_Num>(edge.size());
  }
  std::vector<SCOTCH_Num> mine(static_cast<size_t>(hi - lo) + 1);  // +1: never a null array
  auto fail = [](const char* what) {
    throw EnvironmentError("PT-Scotch", std::string(what) + " failed");
  };
  SCOTCH_Dgraph g, bound;
  SCOTCH_Strat strat;
  SCOTCH_Context ctx;
  if (SCOTCH_dgraphInit(&g, MPI_COMM_WORLD) != 0) fail("SCOTCH_dgraphInit");
  SCOTCH_stratInit(&strat);
  SCOTCH_contextInit(&ctx);
  bool is_bound = false;
  struct Free {  // on every path out
    SCOTCH_Dgraph *g, *bound;
    SCOTCH_Strat* s;
    SCOTCH_Context* c;
    const bool* is_bound;
    ~Free() {
      if (*is_bound) SCOTCH_dgraphExit(bound);
      SCOTCH_contextExit(c);
      SCOTCH_stratExit(s);
      SCOTCH_dgraphExit(g);
    }
  } free_them{&g, &bound, &strat, &ctx, &is_bound};
  // As the sequential scotch partition (core/partition.cc): deterministic, the seed fixed, so a
  // job computes the same parts every time (message arrival order no longer matters).
  if (SCOTCH_contextOptionSetNum(&ctx, SCOTCH_OPTIONNUMDETERMINISTIC, 1) != 0 ||
      SCOTCH_contextOptionSetNum(&ctx, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1) != 0)
    fail("SCOTCH_contextOptionSetNum");
  // One thread per rank: the ranks already fill the cores, and Scotch's default (a thread per
  // core in every rank) put 16 x 16 threads on the 16-core machine.
  if (SCOTCH_contextThreadSpawn(&ctx, 1, nullptr) != 0) fail("SCOTCH_contextThreadSpawn");
  SCOTCH_contextRandomSeed(&ctx, static_cast<SCOTCH_Num>(seed & 0x7FFFFFFF));
  SCOTCH_contextRandomReset(&ctx);
  const auto nloc = static_cast<SCOTCH_Num>(hi - lo), eloc = static_cast<SCOTCH_Num>(edge.size());
  if (SCOTCH_dgraphBuild(&g, 0, nloc, nloc, vert.data(), nullptr, nullptr, nullptr, eloc, eloc,
                         edge.data(), nullptr, nullptr) != 0)
    fail("SCOTCH_dgraphBuild");
  if (SCOTCH_contextBindDgraph(&ctx, &g, &bound) != 0) fail("SCOTCH_contextBindDgraph");
  is_bound = true;
  if (SCOTCH_stratDgraphMapBuild(&strat, SCOTCH_STRATBALANCE, parts, parts, 0.03) != 0)
    fail("SCOTCH_stratDgraphMapBuild");
  if (SCOTCH_dgraphPart(&bound, parts, &strat, mine.data()) != 0) fail("SCOTCH_dgraphPart");
  // Every vertex's part on every rank (the whole-mesh layout of core/rank_part.h needs them all).
  std::vector<int32_t> local(static_cast<size_t>(hi - lo)), all(static_cast<size_t>(n));
  for (int64_t i = 0; i < hi - lo; ++i) local[i] = static_cast<int32_t>(mine[i]);
  std::vector<int> counts(static_cast<size_t>(size)), at(static_cast<size_t>(size));
  for (int r = 0; r < size; ++r) {
    at[r] = static_cast<int>(RangeFirst(r, n, parts));  // n < 2^31: ids are int32
    counts[r] = static_cast<int>(RangeFirst(r + 1, n, parts) - RangeFirst(r, n, parts));
  }
  MPI_Allgatherv(local.data(), static_cast<int>(local.size()), MPI_INT32_T, all.data(),
                 counts.data(), at.data(), MPI_INT32_T, MPI_COMM_WORLD);
  for (int32_t p : all)
    if (p < 0 || p >= parts) throw std::logic_error("PtScotchParts: a part out of range");
  return all;
}

}  // namespace meshreuse::cli
