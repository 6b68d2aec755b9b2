// PtScotchParts (mpi_ptscotch.h): SCOTCH_dgraphPart on the mesh's vertex graph, each rank its range
// of rows.
#include "cli/mpi_ptscotch.h"

#include <mpi.h>
#include <ptscotch.h>
#include <scotch.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/error.h"
#include "core/ranks/rank_neighbourhood.h"

namespace meshreuse::cli {

std::vector<int32_t> PtScotchParts(const GraphRows& rows, int32_t parts, uint64_t seed) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (parts != size) throw std::invalid_argument("PtScotchParts: one part per rank of the job");
  const int64_t lo = RangeFirst(rank, rows.vertices, parts);
  const int64_t hi = RangeFirst(rank + 1, rows.vertices, parts);
  if (rows.first != lo || static_cast<int64_t>(rows.off.size()) != hi - lo + 1)
    throw std::invalid_argument("PtScotchParts: rows of another range");
  // SCOTCH_Num is int64 (scotch-int64): the rows go as they are, no copy (Scotch only reads a
  // graph it is given; the rows are half a rank's memory at this point).
  static_assert(std::is_same<SCOTCH_Num, int64_t>::value, "64-bit Scotch");
  SCOTCH_Num none = 0;  // never a null array
  auto* vert = const_cast<SCOTCH_Num*>(rows.off.data());
  auto* edge = rows.adj.empty() ? &none : const_cast<SCOTCH_Num*>(rows.adj.data());
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
  // As the sequential scotch partition (core/ranks/partition.cc): deterministic, the seed fixed, so
  // a job computes the same parts every time (message arrival order no longer matters).
  if (SCOTCH_contextOptionSetNum(&ctx, SCOTCH_OPTIONNUMDETERMINISTIC, 1) != 0 ||
      SCOTCH_contextOptionSetNum(&ctx, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1) != 0)
    fail("SCOTCH_contextOptionSetNum");
  // One thread per rank: the ranks already fill the cores, and Scotch's default (a thread per
  // core in every rank) put 16 x 16 threads on the 16-core machine.
  if (SCOTCH_contextThreadSpawn(&ctx, 1, nullptr) != 0) fail("SCOTCH_contextThreadSpawn");
  SCOTCH_contextRandomSeed(&ctx, static_cast<SCOTCH_Num>(seed & 0x7FFFFFFF));
  SCOTCH_contextRandomReset(&ctx);
  const auto nloc = static_cast<SCOTCH_Num>(hi - lo);
  const auto eloc = static_cast<SCOTCH_Num>(rows.adj.size());
  if (SCOTCH_dgraphBuild(&g, 0, nloc, nloc, vert, nullptr, nullptr, nullptr, eloc, eloc, edge,
                         nullptr, nullptr) != 0)
    fail("SCOTCH_dgraphBuild");
  if (SCOTCH_contextBindDgraph(&ctx, &g, &bound) != 0) fail("SCOTCH_contextBindDgraph");
  is_bound = true;
  if (SCOTCH_stratDgraphMapBuild(&strat, SCOTCH_STRATBALANCE, parts, parts, 0.03) != 0)
    fail("SCOTCH_stratDgraphMapBuild");
  if (SCOTCH_dgraphPart(&bound, parts, &strat, mine.data()) != 0) fail("SCOTCH_dgraphPart");
  std::vector<int32_t> local(static_cast<size_t>(hi - lo));
  for (int64_t i = 0; i < hi - lo; ++i) {
    if (mine[i] < 0 || mine[i] >= parts)
      throw std::logic_error("PtScotchParts: a part out of range");
    local[i] = static_cast<int32_t>(mine[i]);
  }
  return local;
}

}  // namespace meshreuse::cli
