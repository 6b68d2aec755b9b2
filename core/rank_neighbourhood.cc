// A rank's range of a distributed mesh file and its ghost ring; see rank_neighbourhood.h.
#include "core/rank_neighbourhood.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/halo_smoother.h"
#include "core/mesh_file.h"
#include "core/quality.h"
#include "core/radix_sort.h"

namespace meshreuse {

int64_t RangeFirst(int32_t r, int64_t n, int32_t parts) {
  return (int64_t{r} * n + parts - 1) / parts;  // the least i with i * parts / n >= r
}

int32_t RangeOwner(int64_t v, int64_t n, int32_t parts) {
  return static_cast<int32_t>(v * parts / n);
}

RankNeighbourhood ReadRankNeighbourhood(const std::string& path, int32_t rank, int32_t parts,
                                        const GhostLookup& lookup) {
  MeshFile f(path);
  const int64_t n = f.vertices(), nt = f.triangles();
  if (parts > n)
    throw UsageError(std::to_string(parts) + " ranks for a mesh of " + std::to_string(n) +
                     " vertices: at most one rank per vertex");
  if (rank < 0 || rank >= parts) throw std::invalid_argument("ReadRankNeighbourhood: bad rank");
  RankNeighbourhood nb;
  nb.rank = rank, nb.parts = parts, nb.vertices = n, nb.triangles = nt;
  nb.content_id = f.content_id();
  const int64_t lo = RangeFirst(rank, n, parts), hi = RangeFirst(rank + 1, n, parts);
  nb.first = lo, nb.last = hi;
  auto fail = [&](const std::string& what) { throw InputError(path, 0, what); };

  // The owned rows.
  std::vector<int64_t> off(static_cast<size_t>(hi - lo + 1));
  f.Read(MeshFile::kV2tOff, lo, hi - lo + 1, off.data());
  if (lo == 0 && off[0] != 0) fail("v2t row offsets: the first is " + std::to_string(off[0]));
  if (hi == n && off.back() != 3 * nt)
    fail("v2t row offsets: the last is " + std::to_string(off.back()) + ", not 3 x " +
         std::to_string(nt) + " triangles");
  for (int64_t v = lo; v < hi; ++v) {
    const int64_t a = off[v - lo], b = off[v - lo + 1];
    if (a < 0 || b > 3 * nt || b <= a)
      fail("vertex " + std::to_string(v) + ": v2t row [" + std::to_string(a) + ", " +
           std::to_string(b) + ") is empty, reversed or outside 0.." + std::to_string(3 * nt));
  }
  nb.row_entries = off.back() - off.front();
  std::vector<int32_t> rows(static_cast<size_t>(nb.row_entries));
  f.Read(MeshFile::kV2t, off.front(), nb.row_entries, rows.data());
  for (int64_t v = lo; v < hi; ++v)
    for (int64_t k = off[v - lo]; k < off[v - lo + 1]; ++k) {
      const int32_t t = rows[k - off.front()];
      if (t < 0 || t >= nt || (k > off[v - lo] && t <= rows[k - 1 - off.front()]))
        fail("vertex " + std::to_string(v) + ": its v2t row lists triangle " + std::to_string(t) +
             " (out of 0.." + std::to_string(nt - 1) + " or not increasing)");
    }

  // Every triangle the rows list, in increasing id.
  std::vector<int64_t> tris(rows.begin(), rows.end());
  RadixSortUnique(&tris);
  std::vector<int32_t> corners(3 * tris.size());
  f.ReadAt(MeshFile::kTri, tris, corners.data());
  for (size_t i = 0; i < tris.size(); ++i) {
    const int32_t* c = &corners[3 * i];
    for (int k = 0; k < 3; ++k)
      if (c[k] < 0 || c[k] >= n)
        fail("triangle " + std::to_string(tris[i]) + ": corner " + std::to_string(c[k]) +
             " outside 0.." + std::to_string(n - 1));
  }
  // Rows and triangles agree: every (owned corner, triangle read) pair is in the corner's row (a
  // scan of a short row), and there are as many such pairs as row entries; so each row lists
  // exactly the triangles that hold its vertex.
  int64_t pairs = 0;
  for (size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int32_t c = corners[3 * i + k];
      if (c < lo || c >= hi) continue;
      const int32_t* b = &rows[off[c - lo] - off.front()];
      const int32_t* e = &rows[off[c - lo + 1] - off.front()];
      if (std::find(b, e, static_cast<int32_t>(tris[i])) == e)
        fail("triangle " + std::to_string(tris[i]) + " has vertex " + std::to_string(c) +
             " as a corner but is not in its v2t row");
      ++pairs;
    }
  if (pairs != nb.row_entries)  // some row lists a triangle without its vertex: find it
    for (int64_t v = lo; v < hi; ++v)
      for (int64_t k = off[v - lo]; k < off[v - lo + 1]; ++k) {
        const int32_t t = rows[k - off.front()];
        const int32_t* c =
            &corners[3 * (std::lower_bound(tris.begin(), tris.end(), t) - tris.begin())];
        if (c[0] != v && c[1] != v && c[2] != v)
          fail("vertex " + std::to_string(v) + ": its v2t row lists triangle " + std::to_string(t) +
               ", which does not have it as a corner");
      }

  const size_t triangles_here = tris.size();
  std::vector<int32_t>().swap(rows);  // the peak is the mesh built below: keep it lean
  std::vector<int64_t>().swap(tris);

  // The vertices here: owned, and the ghosts (other corners), increasing global id.
  std::vector<int64_t> ghosts;
  for (int32_t c : corners)
    if (c < lo || c >= hi) ghosts.push_back(c);
  RadixSortUnique(&ghosts);
  const auto split = std::lower_bound(ghosts.begin(), ghosts.end(), lo) - ghosts.begin();
  nb.gid.assign(ghosts.begin(), ghosts.begin() + split);
  for (int64_t v = lo; v < hi; ++v) nb.gid.push_back(v);
  nb.gid.insert(nb.gid.end(), ghosts.begin() + split, ghosts.end());
  const size_t total = nb.gid.size();
  // Local ids: owned ones by offset, ghosts by search (few).
  auto local_of = [&, before = split](int64_t g) -> int32_t {
    if (g >= lo && g < hi) return static_cast<int32_t>(before + (g - lo));
    const int64_t i = std::lower_bound(ghosts.begin(), ghosts.end(), g) - ghosts.begin();
    return static_cast<int32_t>(g < lo ? i : i + (hi - lo));
  };

  // The owned vertices' data, then the ghosts' from their owners (or the file).
  std::vector<uint8_t> flag(static_cast<size_t>(hi - lo));
  RawMesh raw;
  raw.vertex_file = raw.triangle_file = path;
  raw.xy.resize(2 * total);
  const size_t before = static_cast<size_t>(split);
  f.Read(MeshFile::kXy, lo, hi - lo, raw.xy.data() + 2 * before);
  f.Read(MeshFile::kBoundary, lo, hi - lo, flag.data());
  const OwnedLookup own = [&](int64_t g) {
    if (g < lo || g >= hi)
      throw InputError(path, 0,
                       "rank " + std::to_string(rank) + " was asked for vertex " +
                           std::to_string(g) + ", which it does not own");
    const size_t l = before + static_cast<size_t>(g - lo);
    return GhostRecord{raw.xy[2 * l], raw.xy[2 * l + 1], off[g - lo + 1] - off[g - lo],
                       flag[g - lo]};
  };
  std::vector<GhostRecord> ghost;
  if (lookup) {
    GhostRequest req{path, nb.content_id, n, ghosts, std::vector<int32_t>(ghosts.size())};
    for (size_t i = 0; i < ghosts.size(); ++i) req.owner[i] = RangeOwner(ghosts[i], n, parts);
    ghost = lookup(req, own);
  } else {
    std::vector<double> gxy(2 * ghosts.size());
    std::vector<uint8_t> gflag(ghosts.size());
    std::vector<int64_t> goff_at, goff(2 * ghosts.size());
    for (int64_t g : ghosts) goff_at.push_back(g), goff_at.push_back(g + 1);
    f.ReadAt(MeshFile::kXy, ghosts, gxy.data());
    f.ReadAt(MeshFile::kBoundary, ghosts, gflag.data());
    f.ReadAt(MeshFile::kV2tOff, goff_at, goff.data());
    for (size_t i = 0; i < ghosts.size(); ++i) {
      if (goff[2 * i] < 0 || goff[2 * i + 1] > 3 * nt || goff[2 * i + 1] < goff[2 * i])
        fail("vertex " + std::to_string(ghosts[i]) + ": v2t row [" + std::to_string(goff[2 * i]) +
             ", " + std::to_string(goff[2 * i + 1]) + ") is reversed or outside 0.." +
             std::to_string(3 * nt));
      ghost.push_back({gxy[2 * i], gxy[2 * i + 1], goff[2 * i + 1] - goff[2 * i], gflag[i]});
    }
  }
  if (ghost.size() != ghosts.size())
    throw std::logic_error("ReadRankNeighbourhood: a ghost lookup answered the wrong count");
  for (size_t i = 0; i < ghosts.size(); ++i) {
    const size_t l = i < before ? i : i + static_cast<size_t>(hi - lo);
    raw.xy[2 * l] = ghost[i].x, raw.xy[2 * l + 1] = ghost[i].y;
  }
  raw.tri.resize(corners.size());
  for (size_t k = 0; k < corners.size(); ++k) raw.tri[k] = local_of(corners[k]);
  std::vector<int32_t>().swap(corners);
  for (int64_t g : nb.gid) raw.vertex_tag.Push(g);  // BuildMesh's messages name global ids
  BuildReport report;
  nb.mesh = BuildMesh(std::move(raw), &report);
  if (!report.kept.empty())  // every vertex here is a corner of a triangle read
    throw std::logic_error(
        "ReadRankNeighbourhood: a vertex of the neighbourhood lies in no triangle");

  // Boundary flags: the owned ones checked, the ghosts' taken from the file (their owners check).
  for (int64_t v = lo; v < hi; ++v) {
    const uint8_t mine = nb.mesh.boundary[local_of(v)];
    if (flag[v - lo] != mine)
      fail("vertex " + std::to_string(v) + ": boundary flag " + std::to_string(flag[v - lo]) +
           ", but its triangles make it " + (mine ? "a boundary" : "an interior") + " vertex");
  }
  for (size_t i = 0; i < ghosts.size(); ++i) {
    if (ghost[i].boundary > 1)
      fail("vertex " + std::to_string(ghosts[i]) + ": boundary flag " +
           std::to_string(ghost[i].boundary) + " (0 or 1)");
    nb.mesh.boundary[local_of(ghosts[i])] = ghost[i].boundary;
  }
  nb.mesh.interior.clear();
  for (size_t l = 0; l < total; ++l)
    if (!nb.mesh.boundary[l]) nb.mesh.interior.push_back(static_cast<int32_t>(l));

  nb.part.resize(total);
  for (size_t l = 0; l < total; ++l) nb.part[l] = RangeOwner(nb.gid[l], n, parts);
  // Global row sizes (triangles at each corner) for the quality weights, as GlobalQualityWeight.
  std::vector<int64_t> row(total);
  for (size_t i = 0; i < ghosts.size(); ++i) {
    const int64_t here = nb.mesh.v2t.RowSize(local_of(ghosts[i]));
    if (ghost[i].triangles < here)
      fail("vertex " + std::to_string(ghosts[i]) + ": its v2t row has " +
           std::to_string(ghost[i].triangles) + " triangles, fewer than the " +
           std::to_string(here) + " that hold it");
    row[local_of(ghosts[i])] = ghost[i].triangles;
  }
  for (int64_t v = lo; v < hi; ++v) row[local_of(v)] = off[v - lo + 1] - off[v - lo];
  const double inv_v = 1.0 / static_cast<double>(n);
  nb.weight.resize(triangles_here);
  for (size_t t = 0; t < triangles_here; ++t) {
    const int32_t* c = &nb.mesh.tri[3 * t];
    nb.weight[t] = QualityWeightOf(inv_v, row[c[0]], row[c[1]], row[c[2]]);
    const int64_t smallest = nb.gid[std::min(c[0], std::min(c[1], c[2]))];
    nb.owned_triangles += smallest >= lo && smallest < hi;
  }
  for (int64_t v = lo; v < hi; ++v) {
    const int32_t l = local_of(v);
    for (const int32_t* u = nb.mesh.v2v.RowBegin(l); u != nb.mesh.v2v.RowEnd(l); ++u)
      if (nb.part[*u] != rank) {
        nb.neighbours.push_back(nb.part[*u]);
        nb.cut_edges += nb.gid[*u] > v;
      }
  }
  std::sort(nb.neighbours.begin(), nb.neighbours.end());
  nb.neighbours.erase(std::unique(nb.neighbours.begin(), nb.neighbours.end()), nb.neighbours.end());
  nb.bytes_read = f.bytes_read();
  return nb;
}

GhostLookup GhostExchange(HaloTransport& tx) {
  return [&tx](const GhostRequest& req, const OwnedLookup& mine) {
    const int32_t P = tx.size(), me = tx.rank();
    const std::vector<int64_t>& wanted = req.wanted;
    const std::vector<int32_t>& owner = req.owner;
    // The file's identity, then whom I ask and for how many: (rank, count) pairs, all-gathered.
    std::vector<int64_t> need = {static_cast<int64_t>(req.content_id), req.vertices};
    for (size_t i = 0; i < wanted.size(); ++i) {
      if (owner[i] == me || owner[i] < 0 || owner[i] >= P)
        throw std::logic_error("GhostExchange: a ghost owned by its own rank or none");
      if (need.size() == 2 || need[need.size() - 2] != owner[i])
        need.push_back(owner[i]), need.push_back(0);
      ++need.back();
    }
    const std::vector<std::string> all =
        tx.AllGather(std::string(reinterpret_cast<const char*>(need.data()), 8 * need.size()));
    std::vector<std::vector<int64_t>> asks(P);
    for (int32_t p = 0; p < P; ++p) {
      if (static_cast<int32_t>(all.size()) != P || all[p].size() % 16 || all[p].empty())
        throw std::logic_error("GhostExchange: a malformed all-gather");
      asks[p].resize(all[p].size() / 8);
      std::memcpy(asks[p].data(), all[p].data(), all[p].size());
      if (asks[p][0] != asks[0][0] || asks[p][1] != asks[0][1])
        throw InputError(req.path, 0,
                         "rank " + std::to_string(p) + " read another mesh file than rank 0 " +
                             "(content ids differ): every rank must see the same file");
    }
    // Requests out: the global ids (exact in a double: ids are below 2^31).
    std::vector<std::vector<double>> request(P), answer(P);
    for (size_t i = 0; i < wanted.size(); ++i)
      request[owner[i]].push_back(static_cast<double>(wanted[i]));
    for (int32_t q = 0; q < P; ++q)
      if (!request[q].empty()) tx.Send(q, request[q].data(), request[q].size());
    // Answers to whoever asked me, in rank order.
    for (int32_t p = 0; p < P; ++p) {
      const std::vector<int64_t>& pairs = asks[p];
      for (size_t k = 2; k < pairs.size(); k += 2) {
        if (pairs[k] != me) continue;
        std::vector<double> ids(static_cast<size_t>(pairs[k + 1]));
        tx.Recv(p, ids.data(), ids.size());
        std::vector<double>& a = answer[p];
        for (double id : ids) {
          const GhostRecord g = mine(static_cast<int64_t>(id));
          a.insert(a.end(),
                   {g.x, g.y, static_cast<double>(g.triangles), static_cast<double>(g.boundary)});
        }
        tx.Send(p, a.data(), a.size());
      }
    }
    // My answers, in the order asked.
    std::vector<GhostRecord> out(wanted.size());
    size_t at = 0;
    for (int32_t q = 0; q < P; ++q) {
      if (request[q].empty()) continue;
      std::vector<double> a(4 * request[q].size());
      tx.Recv(q, a.data(), a.size());
      for (size_t k = 0; k < request[q].size(); ++k, ++at)
        out[at] = {a[4 * k], a[4 * k + 1], static_cast<int64_t>(a[4 * k + 2]),
                   static_cast<uint8_t>(a[4 * k + 3])};
    }
    tx.Flush();
    return out;
  };
}

RankShare ShareOf(const RankNeighbourhood& nb) {
  return {nb.content_id,  nb.vertices,  nb.triangles, nb.owned_triangles,
          nb.row_entries, nb.cut_edges, nb.neighbours};
}

std::string PackShare(const RankShare& s) {
  std::string b(sizeof(uint64_t) + 5 * sizeof(int64_t), '\0');
  char* p = &b[0];
  std::memcpy(p, &s.content_id, 8);
  const int64_t v[5] = {s.vertices, s.triangles, s.owned_triangles, s.row_entries, s.cut_edges};
  std::memcpy(p + 8, v, sizeof v);
  b.append(reinterpret_cast<const char*>(s.neighbours.data()), 4 * s.neighbours.size());
  return b;
}

RankShare UnpackShare(const std::string& b) {
  if (b.size() < 48 || (b.size() - 48) % 4) throw std::logic_error("UnpackShare: bad size");
  RankShare s;
  int64_t v[5];
  std::memcpy(&s.content_id, b.data(), 8);
  std::memcpy(v, b.data() + 8, sizeof v);
  s.vertices = v[0], s.triangles = v[1], s.owned_triangles = v[2], s.row_entries = v[3];
  s.cut_edges = v[4];
  s.neighbours.resize((b.size() - 48) / 4);
  if (!s.neighbours.empty()) std::memcpy(s.neighbours.data(), b.data() + 48, b.size() - 48);
  return s;
}

std::vector<std::vector<int32_t>> CheckRankShares(const std::string& path,
                                                  const std::vector<RankShare>& shares) {
  const int32_t parts = static_cast<int32_t>(shares.size());
  int64_t tris = 0, entries = 0;
  for (int32_t r = 0; r < parts; ++r) {
    const RankShare& s = shares[r];
    if (s.content_id != shares[0].content_id)
      throw InputError(path, 0,
                       "rank " + std::to_string(r) +
                           " read another mesh file than rank 0 (content "
                           "ids differ): every rank must see the same file");
    tris += s.owned_triangles, entries += s.row_entries;
  }
  const int64_t nt = parts ? shares[0].triangles : 0;
  if (tris != nt || entries != 3 * nt)
    throw InputError(path, 0,
                     "the ranks found " + std::to_string(tris) + " triangles and " +
                         std::to_string(entries) + " v2t entries, the header says " +
                         std::to_string(nt) + " triangles (a triangle that no v2t row lists)");
  std::vector<std::vector<int32_t>> g(parts);
  for (int32_t r = 0; r < parts; ++r) {
    for (int32_t q : shares[r].neighbours) {
      const auto& back = shares[q < 0 || q >= parts ? r : q].neighbours;
      if (q < 0 || q >= parts || q == r || !std::binary_search(back.begin(), back.end(), r))
        throw InputError(path, 0,
                         "ranks " + std::to_string(r) + " and " + std::to_string(q) +
                             " disagree on whether they are neighbours");
    }
    g[r] = shares[r].neighbours;
  }
  return g;
}

}  // namespace meshreuse
