// One rank's part: the layout and the lists of rank_part.h, computed from the whole mesh.
#include "core/ranks/rank_part.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>

#include "core/error.h"
#include "core/orderings/registry.h"
#include "core/progress.h"
#include "core/quality.h"
#include "core/radix_sort.h"

namespace meshreuse {

const char* CutPlacementName(CutPlacement c) {
  switch (c) {
    case CutPlacement::kLast:
      return "last";
    case CutPlacement::kFirst:
      return "first";
    case CutPlacement::kInterleaved:
      return "interleaved";
  }
  return "?";
}

CutPlacement ParseCutPlacement(const std::string& s) {
  for (CutPlacement c : {CutPlacement::kLast, CutPlacement::kFirst, CutPlacement::kInterleaved})
    if (s == CutPlacementName(c)) return c;
  throw UsageError("--cut-placement must be last, first or interleaved, not '" + s + "'");
}

namespace {

// The part from `m`, a mesh holding at least the rank's vertices and their ghost ring with the
// owned vertices' rows complete: the whole mesh (gid and weight null: ids are global, weights
// computed from it) or a rank's neighbourhood (local ids increasing with the global ids `gid`,
// `weight` per triangle given).
// Builds the part phase by phase (each method one step of the layout, in order); the state the
// steps share is the builder's.
class PartBuilder {
 public:
  PartBuilder(const Mesh& m, const std::vector<int32_t>& part, int32_t parts,
              const std::vector<int32_t>& colour, int32_t rank, const OrderingSpec& ordering,
              uint64_t seed, CutPlacement placement, const int64_t* gid, const double* weight)
      : m(m),
        part(part),
        colour(colour),
        rank(rank),
        spec(ordering),
        ordering(ordering),
        seed(seed),
        placement(placement),
        gid(gid),
        weight(weight),
        n(m.NumVertices()) {
    if (static_cast<int64_t>(part.size()) != n || static_cast<int32_t>(colour.size()) != parts ||
        rank < 0 || rank >= parts)
      throw std::invalid_argument("BuildRankPart: partition, colouring and rank disagree");
    p.rank = rank, p.parts = parts, p.colour = colour[rank], p.placement = placement;
    p.colours = parts ? *std::max_element(colour.begin(), colour.end()) + 1 : 1;
  }
  RankPart Build() {
    // Progress in steps (core/progress.h): a part of 10^7 vertices takes tens of seconds.
    Gather();
    ReportProgress(1, 6);
    Positions();
    ReportProgress(2, 6);
    Layout();
    ReportProgress(3, 6);
    Rows();
    ReportProgress(4, 6);
    Triangles();
    ReportProgress(5, 6);
    Links();
    ReportProgress(6, 6);
    return std::move(p);
  }

 private:
  void Gather() {
    // The vertices here, by global id: owned, then the ghost ring.
    local.assign(static_cast<size_t>(n), -1);
    for (int32_t v = 0; v < n; ++v)
      if (part[v] == rank) {
        local[v] = 0;
        for (const int32_t* u = m.v2v.RowBegin(v); u != m.v2v.RowEnd(v); ++u)
          if (part[*u] != rank) local[*u] = 0;
      }
    for (int32_t v = 0; v < n; ++v)
      if (local[v] == 0) mine.push_back(v);
  }
  void Positions() {
    // The position of each in the rank's ordering: `ori` keeps global ids; any other ordering runs
    // on the part with its ghost ring and every triangle with an owned corner, a mesh of its own.
    pos.resize(mine.size());
    if (gid) {  // a neighbourhood holds those triangles only (and may have dropped its v2t)
      tris.resize(static_cast<size_t>(m.NumTriangles()));
      std::iota(tris.begin(), tris.end(), 0);
    } else {
      for (int32_t v : mine)
        if (part[v] == rank)
          for (const int32_t* t = m.v2t.RowBegin(v); t != m.v2t.RowEnd(v); ++t) tris.push_back(*t);
      RadixSortUnique(&tris);
    }
    for (size_t i = 0; i < mine.size(); ++i) local[mine[i]] = static_cast<int32_t>(i);
    if (spec.name == "ori" || mine.empty()) {
      for (size_t i = 0; i < mine.size(); ++i) pos[i] = mine[i];
    } else {
      RawMesh raw;
      raw.xy.resize(2 * mine.size());
      for (size_t i = 0; i < mine.size(); ++i) {
        raw.xy[2 * i] = m.xy[2 * int64_t{mine[i]}];
        raw.xy[2 * i + 1] = m.xy[2 * int64_t{mine[i]} + 1];
      }
      raw.tri.reserve(3 * tris.size());
      for (int32_t t : tris)
        for (int k = 0; k < 3; ++k) raw.tri.push_back(local[m.tri[3 * int64_t{t} + k]]);
      raw.vertex_file = raw.triangle_file = "rank " + std::to_string(rank) + "'s part";
      BuildReport report;
      const Mesh sub = BuildMesh(std::move(raw), &report);
      if (!report.kept.empty())  // every ghost shares an edge, hence a triangle, with an owned one
        throw std::logic_error("BuildRankPart: a vertex of the part lies in no triangle");
      const Permutation perm = ComputeOrdering(ordering, sub, seed);
      for (size_t i = 0; i < mine.size(); ++i) pos[i] = perm.NewOf(static_cast<int32_t>(i));
    }
  }
  void Layout() {
    // Groups: 0 non-cut interior, 1 cut interior, 2 owned boundary, 3 ghost; each by position.
    group.resize(mine.size());
    for (size_t i = 0; i < mine.size(); ++i) {
      const int32_t v = mine[i];
      if (part[v] != rank) {
        group[i] = 3;
      } else if (m.boundary[v]) {
        group[i] = 2;
      } else {
        group[i] = 0;
        for (const int32_t* u = m.v2v.RowBegin(v); u != m.v2v.RowEnd(v); ++u)
          if (part[*u] != rank) group[i] = 1;
      }
    }
    // The storage (and visit) rank of each group: cut before non-cut with kFirst, one movable
    // group with kInterleaved.
    const int8_t rank_of[3][4] = {{0, 1, 2, 3}, {1, 0, 2, 3}, {0, 0, 2, 3}};
    const int8_t* key = rank_of[static_cast<int>(placement)];
    // Sorted by (group key, position) in O(n): the vertices in position order (`ori`'s positions
    // increase with i; any other ordering's are a permutation of 0..n-1), then a stable bucketing
    // by key.
    std::vector<int32_t> by_pos(mine.size());
    if (spec.name == "ori" || mine.empty())
      std::iota(by_pos.begin(), by_pos.end(), 0);
    else
      for (size_t i = 0; i < mine.size(); ++i) by_pos[pos[i]] = static_cast<int32_t>(i);
    std::vector<int32_t> at;
    at.reserve(mine.size());
    for (int8_t k = 0; k < 4; ++k)
      for (int32_t i : by_pos)
        if (key[group[i]] == k) at.push_back(i);
    p.total = static_cast<int32_t>(mine.size());
    p.gid.resize(mine.size());
    p.xy.resize(2 * mine.size());
    vert.resize(mine.size());
    int32_t ends[4] = {0, 0, 0, 0};
    for (int32_t k = 0; k < p.total; ++k) {
      const int32_t v = mine[at[k]];
      p.gid[k] = gid ? gid[v] : v;
      vert[k] = v;
      p.xy[2 * int64_t{k}] = m.xy[2 * int64_t{v}];
      p.xy[2 * int64_t{k} + 1] = m.xy[2 * int64_t{v} + 1];
      local[v] = k;
      ++ends[group[at[k]]];
    }
    p.noncut = ends[0];
    p.movable = ends[0] + ends[1];
    p.owned = p.movable + ends[2];
  }
  void Rows() {
    // Neighbour rows of the movable vertices, in the serial mesh's (increasing global id) order.
    p.v2v.off.assign(p.movable + 1, 0);
    for (int32_t k = 0; k < p.movable; ++k) {
      const int32_t v = vert[k];
      for (const int32_t* u = m.v2v.RowBegin(v); u != m.v2v.RowEnd(v); ++u)
        p.v2v.idx.push_back(local[*u]);
      p.v2v.off[k + 1] = static_cast<int64_t>(p.v2v.idx.size());
    }
  }
  void Triangles() {
    // Triangles owned here: those whose smallest corner (global id) is owned. With `ori` in the
    // input's order (the part as stored, like the paper's ORI); with any other ordering stably by
    // their smallest local corner, as `reorder` stores a reordered mesh's (TriangleOrder::kSorted),
    // so the quality pass follows the rank's layout rather than the input's triangle order (a file
    // in random order at -np 2 with `--ordering hilbert`: 110 ms a sweep before, 32 after; bfs and
    // grid-wave parts of plate6 1.7x and 2.1x faster; but ori on a pieces-layout file 9% slower
    // sorted, so ori keeps the file's). The quality is an exact sum: the order costs no bit. A
    // counting sort placed straight into the part's arrays: no second copy of them.
    auto owned_here = [&](int32_t t) {
      const int32_t* c = &m.tri[3 * int64_t{t}];
      return part[std::min(c[0], std::min(c[1], c[2]))] == rank;
    };
    auto smallest = [&](int32_t t) {
      const int32_t* c = &m.tri[3 * int64_t{t}];
      return std::min(local[c[0]], std::min(local[c[1]], local[c[2]]));
    };
    const bool as_stored = spec.name == "ori";
    int64_t seen = 0;  // with ori, the key is the position among the owned triangles
    std::vector<int64_t> start(static_cast<size_t>(p.total) + 1, 0);
    for (int32_t t : tris)
      if (owned_here(t)) ++start[as_stored ? 0 : smallest(t) + 1];
    for (size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    p.tri.resize(3 * static_cast<size_t>(start.back()));
    p.weight.resize(static_cast<size_t>(start.back()));
    for (int32_t t : tris) {
      if (!owned_here(t)) continue;
      const int64_t to = as_stored ? seen++ : start[smallest(t)]++;
      const int32_t* c = &m.tri[3 * int64_t{t}];
      for (int k = 0; k < 3; ++k) p.tri[3 * to + k] = local[c[k]];
      p.weight[to] = weight ? weight[t] : GlobalQualityWeight(m, t);
    }
  }
  void Links() {
    // Links, both lists by increasing global id (`mine` is).
    std::map<int32_t, RankLink> links;
    for (int32_t v : mine) {
      const int32_t k = local[v];
      if (part[v] == rank && k < p.movable) {
        int32_t last = -1;  // rows are sorted by id, not by part: collect the distinct parts
        std::vector<int32_t> to;
        for (const int32_t* u = m.v2v.RowBegin(v); u != m.v2v.RowEnd(v); ++u)
          if (part[*u] != rank && part[*u] != last) to.push_back(last = part[*u]);
        std::sort(to.begin(), to.end());
        to.erase(std::unique(to.begin(), to.end()), to.end());
        for (int32_t q : to) links[q].send.push_back(k);
      } else if (part[v] != rank && !m.boundary[v]) {
        links[part[v]].recv.push_back(k);
      }
    }
    for (auto& [q, l] : links) {
      l.rank = q;
      l.colour = colour[q];
      if (l.colour == p.colour)
        throw std::invalid_argument("BuildRankPart: neighbouring parts " + std::to_string(rank) +
                                    " and " + std::to_string(q) + " share colour " +
                                    std::to_string(l.colour));
      p.links.push_back(std::move(l));
    }
  }

  const Mesh& m;
  const std::vector<int32_t>& part;
  const std::vector<int32_t>& colour;
  const int32_t rank;
  const OrderingSpec& spec;
  const OrderingSpec& ordering;
  const uint64_t seed;
  const CutPlacement placement;
  const int64_t* gid;
  const double* weight;
  const int32_t n;
  RankPart p;
  std::vector<int32_t> local;  // vertex of `m` -> local id (-1: not here)
  std::vector<int32_t> mine;   // owned and ghosts, increasing global id
  std::vector<int64_t> pos;    // each one's position in the rank's ordering
  std::vector<int32_t> tris;   // ids (in m) of the triangles with an owned corner
  std::vector<int8_t> group;   // 0 non-cut interior, 1 cut interior, 2 owned boundary, 3 ghost
  std::vector<int32_t> vert;   // local -> vertex of `m`
};

RankPart BuildPart(const Mesh& m, const std::vector<int32_t>& part, int32_t parts,
                   const std::vector<int32_t>& colour, int32_t rank, const OrderingSpec& ordering,
                   uint64_t seed, CutPlacement placement, const int64_t* gid,
                   const double* weight) {
  return PartBuilder(m, part, parts, colour, rank, ordering, seed, placement, gid, weight).Build();
}

}  // namespace

RankPart BuildRankPart(const Mesh& m, const std::vector<int32_t>& part, int32_t parts,
                       const std::vector<int32_t>& colour, int32_t rank,
                       const OrderingSpec& ordering, uint64_t seed, CutPlacement placement) {
  return BuildPart(m, part, parts, colour, rank, ordering, seed, placement, nullptr, nullptr);
}

RankPart BuildRankPart(RankNeighbourhood&& nb, const std::vector<int32_t>& colour,
                       const OrderingSpec& ordering, uint64_t seed, CutPlacement placement) {
  // What the layout does not read goes first: the peak of a rank's set-up is here.
  decltype(nb.mesh.v2t.off)().swap(nb.mesh.v2t.off);
  decltype(nb.mesh.v2t.idx)().swap(nb.mesh.v2t.idx);
  decltype(nb.mesh.interior)().swap(nb.mesh.interior);
  return BuildRankPart(static_cast<const RankNeighbourhood&>(nb), colour, ordering, seed,
                       placement);
}

RankPart BuildRankPart(const RankNeighbourhood& nb, const std::vector<int32_t>& colour,
                       const OrderingSpec& ordering, uint64_t seed, CutPlacement placement) {
  if (nb.gid.size() != static_cast<size_t>(nb.mesh.NumVertices()) ||
      nb.weight.size() != static_cast<size_t>(nb.mesh.NumTriangles()))
    throw std::invalid_argument("BuildRankPart: an inconsistent neighbourhood");
  return BuildPart(nb.mesh, nb.part, nb.parts, colour, nb.rank, ordering, seed, placement,
                   nb.gid.data(), nb.weight.data());
}

std::vector<int64_t> VisitOrderOf(const std::vector<RankMoves>& ranks) {
  std::vector<int64_t> pi;
  int32_t colours = 0;
  for (const RankMoves& r : ranks) colours = std::max(colours, r.colour + 1);
  auto add = [&pi](const RankMoves& r, size_t b, size_t e) {
    pi.insert(pi.end(), r.gid.begin() + b, r.gid.begin() + e);
  };
  auto noncut = [&] {
    for (const RankMoves& r : ranks) {
      const size_t cut = r.gid.size() - r.noncut;
      r.placement == CutPlacement::kFirst ? add(r, cut, r.gid.size()) : add(r, 0, r.noncut);
    }
  };
  auto by_colour = [&](bool whole) {
    for (int32_t c = 0; c < colours; ++c)
      for (const RankMoves& r : ranks) {
        if (r.colour != c) continue;
        const size_t cut = r.gid.size() - r.noncut;
        if (whole)
          add(r, 0, r.gid.size());
        else
          r.placement == CutPlacement::kFirst ? add(r, 0, cut) : add(r, r.noncut, r.gid.size());
      }
  };
  const CutPlacement placement = ranks.empty() ? CutPlacement::kLast : ranks[0].placement;
  for (const RankMoves& r : ranks)
    if (r.placement != placement) throw std::invalid_argument("VisitOrderOf: mixed placements");
  if (placement == CutPlacement::kLast) noncut(), by_colour(false);
  if (placement == CutPlacement::kFirst) by_colour(false), noncut();
  if (placement == CutPlacement::kInterleaved) by_colour(true);
  return pi;
}

std::vector<int64_t> GatheredVisitOrder(const std::vector<RankPart>& parts) {
  std::vector<RankMoves> ranks;
  for (const RankPart& p : parts)
    ranks.push_back({p.colour, p.placement, p.noncut,
                     std::vector<int64_t>(p.gid.begin(), p.gid.begin() + p.movable)});
  return VisitOrderOf(ranks);
}

}  // namespace meshreuse
