// Vertex partitions and their cost; see partition.h.
#include "core/ranks/partition.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "core/error.h"
#include "core/orderings/metis_graph.h"
#include "core/orderings/registry.h"
#include "core/ranks/rank_neighbourhood.h"
#include "core/stdout_guard.h"
#include "core/text_file.h"

extern "C" {
#include <scotch.h>
}

namespace meshreuse {

namespace {
void CheckParts(const Mesh& m, int32_t parts) {
  if (parts < 1 || parts > std::max(m.NumVertices(), 1))
    throw UsageError("--parts must be 1.." + std::to_string(std::max(m.NumVertices(), 1)));
}
}  // namespace

std::vector<int32_t> HilbertRangeParts(const Mesh& m, int32_t parts) {
  CheckParts(m, parts);
  const int64_t n = m.NumVertices();
  const Permutation h = ComputeOrdering("hilbert", m);
  std::vector<int32_t> part(n);
  for (int64_t i = 0; i < n; ++i)
    part[h.OldOf(static_cast<int32_t>(i))] = static_cast<int32_t>(i * parts / n);
  return part;
}

std::vector<int32_t> MetisParts(const Mesh& m, int32_t parts, uint64_t seed) {
  CheckParts(m, parts);
  const int32_t n = m.NumVertices();
  if (parts == 1) return std::vector<int32_t>(n, 0);
  orderings::MetisGraph g = orderings::ToMetis(m);
  idx_t ncon = 1, np = parts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = static_cast<idx_t>(seed & 0x7FFFFFFF);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> p(n);
  {
    const StdoutToStderr quiet;  // METIS may printf: stdout holds only results
    orderings::MetisCheck(
        METIS_PartGraphKway(&g.n, &ncon, g.xadj.data(), g.adjncy.data(), nullptr, nullptr, nullptr,
                            &np, nullptr, nullptr, options, &cut, p.data()),
        "METIS_PartGraphKway");
  }
  return std::vector<int32_t>(p.begin(), p.end());
}

std::vector<int32_t> RangeParts(const Mesh& m, int32_t parts) {
  CheckParts(m, parts);
  const int64_t n = m.NumVertices();
  std::vector<int32_t> part(n);
  for (int64_t v = 0; v < n; ++v) part[v] = RangeOwner(v, n, parts);
  return part;
}

std::vector<int32_t> ScotchParts(const Mesh& m, int32_t parts, uint64_t seed) {
  CheckParts(m, parts);
  const int32_t n = m.NumVertices();
  if (parts == 1) return std::vector<int32_t>(n, 0);
  std::vector<SCOTCH_Num> vert(m.v2v.off.begin(), m.v2v.off.end());
  std::vector<SCOTCH_Num> edge(m.v2v.idx.begin(), m.v2v.idx.end());
  std::vector<SCOTCH_Num> out(static_cast<size_t>(n));
  auto check = [](int rc, const char* what) {
    if (rc != 0) throw std::runtime_error(std::string("Scotch: ") + what + " failed");
  };
  const StdoutToStderr quiet;  // one partitioner at a time in a process; Scotch's errors on stderr
  SCOTCH_Graph g;
  SCOTCH_Strat strat;
  SCOTCH_Context ctx;
  check(SCOTCH_graphInit(&g), "graphInit");
  check(SCOTCH_stratInit(&strat), "stratInit");
  check(SCOTCH_contextInit(&ctx), "contextInit");
  struct Cleanup {
    SCOTCH_Graph* g;
    SCOTCH_Strat* s;
    SCOTCH_Context* c;
    ~Cleanup() {
      SCOTCH_contextExit(c);
      SCOTCH_stratExit(s);
      SCOTCH_graphExit(g);
    }
  } cleanup{&g, &strat, &ctx};
  // Deterministic and seeded, so every rank computes the same parts independently.
  check(SCOTCH_contextOptionSetNum(&ctx, SCOTCH_OPTIONNUMDETERMINISTIC, 1), "deterministic");
  check(SCOTCH_contextOptionSetNum(&ctx, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1), "fixed seed");
  SCOTCH_contextRandomSeed(&ctx, static_cast<SCOTCH_Num>(seed & 0x7FFFFFFF));
  SCOTCH_contextRandomReset(&ctx);
  check(SCOTCH_graphBuild(&g, 0, n, vert.data(), nullptr, nullptr, nullptr,
                          static_cast<SCOTCH_Num>(edge.size()), edge.data(), nullptr),
        "graphBuild");
  SCOTCH_Graph bound;
  check(SCOTCH_contextBindGraph(&ctx, &g, &bound), "contextBindGraph");
  check(SCOTCH_stratGraphMapBuild(&strat, SCOTCH_STRATBALANCE, parts, 0.03), "stratGraphMapBuild");
  const int rc = SCOTCH_graphPart(&bound, parts, &strat, out.data());
  SCOTCH_graphExit(&bound);
  check(rc, "graphPart");
  return std::vector<int32_t>(out.begin(), out.end());
}

void CheckPartitionMethod(const std::string& method) {
  if (IsPartitionFile(method)) {
    if (method.size() == 5) throw UsageError("--partition file: needs a path (file:PATH)");
    return;  // read (and checked against the mesh) once the mesh is
  }
  if (method != "hilbert" && method != "metis" && method != "scotch" && method != "ranges" &&
      method != "gmsh")
    throw UsageError(
        "--partition must be hilbert, metis, scotch, ranges, gmsh or file:PATH (meshreuse-mpi "
        "smooth also ptscotch), not '" +
        method + "'");
}

std::vector<int32_t> ReadPartitionFile(const std::string& path, int32_t vertices, int32_t parts) {
  TextFile f(path);
  std::vector<int32_t> part;
  part.reserve(static_cast<size_t>(vertices));
  std::string_view line, tok[2];
  while (f.NextDataLine(&line)) {
    if (Tokens(line).Split(tok, 2) != 1) f.Fail("expected one part number per line");
    if (static_cast<int64_t>(part.size()) == vertices)
      f.Fail("more lines than the mesh's " + std::to_string(vertices) + " vertices");
    const int64_t p = f.ParseInt(tok[0], "part");
    if (p < 0 || p >= parts)
      f.Fail("part " + std::to_string(p) + " of vertex " + std::to_string(part.size()) +
             " is outside 0.." + std::to_string(parts - 1) + " (" + std::to_string(parts) +
             " ranks)");
    part.push_back(static_cast<int32_t>(p));
  }
  if (static_cast<int64_t>(part.size()) != vertices)
    throw InputError(path, 0,
                     std::to_string(part.size()) + " parts for a mesh of " +
                         std::to_string(vertices) + " vertices: a line per vertex");
  return part;
}

std::vector<int32_t> PartsByMethod(const Mesh& m, const std::string& method, int32_t parts,
                                   uint64_t seed) {
  CheckPartitionMethod(method);
  if (IsPartitionFile(method)) return ReadPartitionFile(method.substr(5), m.NumVertices(), parts);
  if (method == "ranges") return RangeParts(m, parts);
  if (method == "scotch") return ScotchParts(m, parts, seed);
  if (method == "gmsh")
    throw UsageError("--partition gmsh takes its parts from a Gmsh split set (PREFIX_K.msh)");
  return method == "metis" ? MetisParts(m, parts, seed) : HilbertRangeParts(m, parts);
}

double PartitionStats::imbalance() const {
  if (owned.empty()) return 0;
  int64_t sum = 0, mx = 0;
  for (int64_t o : owned) sum += o, mx = std::max(mx, o);
  return sum ? static_cast<double>(mx) * static_cast<double>(owned.size()) /
                   static_cast<double>(sum)
             : 0;
}

PartitionStats MeasurePartition(const Mesh& m, const std::vector<int32_t>& part, int32_t parts,
                                const std::string& name) {
  const int32_t n = m.NumVertices();
  if (static_cast<int64_t>(part.size()) != n)
    throw InputError(name, 0,
                     std::to_string(part.size()) + " parts for " + std::to_string(n) + " vertices");
  for (int32_t v = 0; v < n; ++v)
    if (part[v] < 0 || part[v] >= parts)
      throw InputError(
          name, v + 1,
          "part " + std::to_string(part[v]) + " outside 0.." + std::to_string(parts - 1));
  PartitionStats s;
  s.parts = parts;
  s.owned.assign(parts, 0);
  s.ghosts.assign(parts, 0);
  s.cut_owned.assign(parts, 0);
  std::vector<std::vector<int32_t>> pnbr(parts);
  // A vertex is one part's ghost once however many of its vertices it neighbours: each part's
  // list of ghost sightings is made unique below.
  std::vector<std::vector<int32_t>> ghost_of(parts);
  for (int32_t v = 0; v < n; ++v) {
    ++s.owned[part[v]];
    bool cut = false;
    for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
      if (part[*q] != part[v]) {
        cut = true;
        s.cut_edges += *q > v;
        pnbr[part[v]].push_back(part[*q]);
        ghost_of[part[v]].push_back(*q);
      }
    s.cut_owned[part[v]] += cut;
  }
  for (int32_t p = 0; p < parts; ++p) {
    auto& g = ghost_of[p];
    std::sort(g.begin(), g.end());
    s.ghosts[p] = std::unique(g.begin(), g.end()) - g.begin();
    std::sort(pnbr[p].begin(), pnbr[p].end());
    pnbr[p].erase(std::unique(pnbr[p].begin(), pnbr[p].end()), pnbr[p].end());
  }
  s.colour = GreedyPartColouring(pnbr, &s.colours);
  return s;
}

std::vector<int32_t> GreedyPartColouring(const std::vector<std::vector<int32_t>>& neighbours,
                                         int32_t* colours) {
  const int32_t parts = static_cast<int32_t>(neighbours.size());
  std::vector<int32_t> colour(parts, -1);
  *colours = 0;
  for (int32_t p = 0; p < parts; ++p) {
    std::vector<uint8_t> used(neighbours[p].size() + 1, 0);
    for (int32_t q : neighbours[p])
      if (q < p && colour[q] < static_cast<int32_t>(used.size())) used[colour[q]] = 1;
    int32_t c = 0;
    while (used[c]) ++c;
    colour[p] = c;
    *colours = std::max(*colours, c + 1);
  }
  return colour;
}

}  // namespace meshreuse
