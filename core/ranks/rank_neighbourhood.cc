// A rank's range of a distributed mesh file and its ghost ring; see rank_neighbourhood.h.
#include "core/ranks/rank_neighbourhood.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/mesh_file.h"
#include "core/quality.h"
#include "core/radix_sort.h"
#include "core/ranks/halo_smoother.h"

namespace meshreuse {

int64_t RangeFirst(int32_t r, int64_t n, int32_t parts) {
  return (int64_t{r} * n + parts - 1) / parts;  // the least i with i * parts / n >= r
}

int32_t RangeOwner(int64_t v, int64_t n, int32_t parts) {
  return static_cast<int32_t>(v * parts / n);
}

SortedIds::SortedIds(const std::vector<int64_t>& ids) {
  for (size_t i = 0; i < ids.size(); ++i) {
    if (i && ids[i] <= ids[i - 1]) throw std::logic_error("SortedIds: ids not increasing");
    if (!i || ids[i] != ids[i - 1] + 1) start_.push_back(ids[i]), pos_.push_back(int64_t(i));
  }
  pos_.push_back(static_cast<int64_t>(ids.size()));
  for (size_t r = 0; r < start_.size(); ++r)
    if (pos_[r + 1] - pos_[r] > big_len_)
      big_first_ = start_[r], big_pos_ = pos_[r], big_len_ = pos_[r + 1] - pos_[r];
}

int64_t SortedIds::Find(int64_t g) const {
  // The longest run first: a range's owned ids are one run beside its ghosts' many short ones.
  if (g >= big_first_ && g - big_first_ < big_len_) return big_pos_ + (g - big_first_);
  const size_t r = std::upper_bound(start_.begin(), start_.end(), g) - start_.begin();
  if (r == 0) return -1;
  const int64_t p = pos_[r - 1] + (g - start_[r - 1]);
  return p < pos_[r] ? p : -1;
}

namespace {

// The owned vertices' v2t rows, every triangle they list and its corners, checked: rows within
// range, increasing and non-empty; corners within range; the rows list exactly the triangles that
// hold each owned vertex (every (owned corner, triangle read) pair in the corner's row, and as
// many pairs as row entries).
struct OwnedRows {
  std::vector<int64_t> start;  // owned vertex k's row is rows[start[k], start[k + 1])
  std::vector<int32_t> rows;
  std::vector<int64_t> tris;     // every triangle the rows list, increasing
  std::vector<int32_t> corners;  // 3 per entry of tris
};

OwnedRows ReadOwnedRows(MeshFile& f, const std::vector<int64_t>& owned, const SortedIds& index) {
  const std::string& path = f.path();
  const int64_t n = f.vertices(), nt = f.triangles();
  auto fail = [&](const std::string& what) { throw InputError(path, 0, what); };
  // Runs of consecutive owned ids: a range partition's one run, a scattered part's many.
  std::vector<int64_t> rf, re;
  for (size_t k = 0; k < owned.size(); ++k)
    if (!k || owned[k] != owned[k - 1] + 1) {
      if (k) re.push_back(owned[k - 1] + 1);
      rf.push_back(owned[k]);
    }
  if (!owned.empty()) re.push_back(owned.back() + 1);
  // Each run's row offsets, one more than its vertices.
  std::vector<int64_t> off(owned.size() + rf.size());
  {
    std::vector<int64_t> re1(re);
    for (int64_t& e : re1) ++e;
    f.ReadRuns(MeshFile::kV2tOff, rf, re1, off.data());
  }
  OwnedRows o;
  o.start.resize(owned.size() + 1);
  std::vector<int64_t> vf(rf.size()), ve(rf.size());  // each run's span of the v2t section
  size_t k = 0, at = 0;
  for (size_t r = 0; r < rf.size(); ++r, ++at) {
    vf[r] = off[at];
    if (rf[r] == 0 && off[at] != 0)
      fail("v2t row offsets: the first is " + std::to_string(off[at]));
    if (r && vf[r] < ve[r - 1])
      fail("vertex " + std::to_string(rf[r]) + ": v2t row offset " + std::to_string(vf[r]) +
           " is below the row of vertex " + std::to_string(re[r - 1] - 1) + "'s end " +
           std::to_string(ve[r - 1]));
    for (int64_t v = rf[r]; v < re[r]; ++v, ++k, ++at) {
      const int64_t a = off[at], b = off[at + 1];
      if (a < 0 || b > 3 * nt || b <= a)
        fail("vertex " + std::to_string(v) + ": v2t row [" + std::to_string(a) + ", " +
             std::to_string(b) + ") is empty, reversed or outside 0.." + std::to_string(3 * nt));
      o.start[k + 1] = o.start[k] + (b - a);
    }
    ve[r] = off[at];
    if (re[r] == n && off[at] != 3 * nt)
      fail("v2t row offsets: the last is " + std::to_string(off[at]) + ", not 3 x " +
           std::to_string(nt) + " triangles");
  }
  std::vector<int64_t>().swap(off);
  o.rows.resize(static_cast<size_t>(o.start.back()));
  f.ReadRuns(MeshFile::kV2t, vf, ve, o.rows.data());
  for (size_t j = 0; j < owned.size(); ++j)
    for (int64_t e = o.start[j]; e < o.start[j + 1]; ++e) {
      const int32_t t = o.rows[e];
      if (t < 0 || t >= nt || (e > o.start[j] && t <= o.rows[e - 1]))
        fail("vertex " + std::to_string(owned[j]) + ": its v2t row lists triangle " +
             std::to_string(t) + " (out of 0.." + std::to_string(nt - 1) + " or not increasing)");
    }

  o.tris.assign(o.rows.begin(), o.rows.end());
  RadixSortUnique(&o.tris);
  o.corners.resize(3 * o.tris.size());
  f.ReadAt(MeshFile::kTri, o.tris, o.corners.data());
  for (size_t i = 0; i < o.tris.size(); ++i) {
    const int32_t* c = &o.corners[3 * i];
    for (int j = 0; j < 3; ++j)
      if (c[j] < 0 || c[j] >= n)
        fail("triangle " + std::to_string(o.tris[i]) + ": corner " + std::to_string(c[j]) +
             " outside 0.." + std::to_string(n - 1));
    // A repeated corner would count one (vertex, triangle) pair twice below, and could balance a
    // row that lists a triangle without its vertex (found by fuzz_mesh_file: ReadRangeGraphRows
    // then overran a row's room).
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
      fail("triangle " + std::to_string(o.tris[i]) + ": degenerate triangle: vertex " +
           std::to_string(c[c[0] == c[1] ? 0 : 2]) + " is used twice");
  }
  int64_t pairs = 0;
  for (size_t i = 0; i < o.tris.size(); ++i)
    for (int j = 0; j < 3; ++j) {
      const int32_t c = o.corners[3 * i + j];
      const int64_t kc = index.Find(c);
      if (kc < 0) continue;
      const int32_t* b = o.rows.data() + o.start[kc];
      const int32_t* e = o.rows.data() + o.start[kc + 1];
      if (std::find(b, e, static_cast<int32_t>(o.tris[i])) == e)
        fail("triangle " + std::to_string(o.tris[i]) + " has vertex " + std::to_string(c) +
             " as a corner but is not in its v2t row");
      ++pairs;
    }
  if (pairs != o.start.back())  // some row lists a triangle without its vertex: find it
    for (size_t j = 0; j < owned.size(); ++j)
      for (int64_t e = o.start[j]; e < o.start[j + 1]; ++e) {
        const int32_t t = o.rows[e];
        const int32_t* c =
            &o.corners[3 * (std::lower_bound(o.tris.begin(), o.tris.end(), t) - o.tris.begin())];
        if (c[0] != owned[j] && c[1] != owned[j] && c[2] != owned[j])
          fail("vertex " + std::to_string(owned[j]) + ": its v2t row lists triangle " +
               std::to_string(t) + ", which does not have it as a corner");
      }
  return o;
}

std::vector<int64_t> RangeIds(int32_t rank, int64_t n, int32_t parts) {
  std::vector<int64_t> ids(
      static_cast<size_t>(RangeFirst(rank + 1, n, parts) - RangeFirst(rank, n, parts)));
  for (size_t k = 0; k < ids.size(); ++k) ids[k] = RangeFirst(rank, n, parts) + int64_t(k);
  return ids;
}

void CheckRanks(int64_t n, int32_t rank, int32_t parts) {
  if (parts > n)
    throw UsageError(std::to_string(parts) + " ranks for a mesh of " + std::to_string(n) +
                     " vertices: at most one rank per vertex");
  if (rank < 0 || rank >= parts) throw std::invalid_argument("a rank outside the job");
}

// The ghosts' data read from the file itself (no owner to ask): coordinates, boundary flags and
// the size of each one's v2t row, checked against the triangle count.
std::vector<GhostRecord> GhostsFromFile(MeshFile& f, const std::vector<int64_t>& ghosts) {
  const int64_t nt = f.triangles();
  std::vector<GhostRecord> ghost;
  std::vector<double> gxy(2 * ghosts.size());
  std::vector<uint8_t> gflag(ghosts.size());
  std::vector<int64_t> goff_at, goff(2 * ghosts.size());
  for (int64_t g : ghosts) goff_at.push_back(g), goff_at.push_back(g + 1);
  f.ReadAt(MeshFile::kXy, ghosts, gxy.data());
  f.ReadAt(MeshFile::kBoundary, ghosts, gflag.data());
  f.ReadAt(MeshFile::kV2tOff, goff_at, goff.data());
  for (size_t i = 0; i < ghosts.size(); ++i) {
    if (goff[2 * i] < 0 || goff[2 * i + 1] > 3 * nt || goff[2 * i + 1] < goff[2 * i])
      throw InputError(f.path(), 0,
                       "vertex " + std::to_string(ghosts[i]) + ": v2t row [" +
                           std::to_string(goff[2 * i]) + ", " + std::to_string(goff[2 * i + 1]) +
                           ") is reversed or outside 0.." + std::to_string(3 * nt));
    ghost.push_back({gxy[2 * i], gxy[2 * i + 1], goff[2 * i + 1] - goff[2 * i], gflag[i]});
  }
  return ghost;
}

// Boundary flags: the owned ones checked, the ghosts' taken from the file (their owners check).
void SetBoundaryFlags(const std::string& path, const std::vector<int64_t>& owned,
                      const std::vector<uint8_t>& flag, const std::vector<int64_t>& ghosts,
                      const std::vector<GhostRecord>& ghost, const SortedIds& local_index,
                      Mesh* mesh) {
  auto fail = [&](const std::string& what) { throw InputError(path, 0, what); };
  auto local_of = [&](int64_t g) { return static_cast<int32_t>(local_index.Find(g)); };
  for (size_t k = 0; k < owned.size(); ++k) {
    const uint8_t mine = mesh->boundary[local_of(owned[k])];
    if (flag[k] != mine)
      fail("vertex " + std::to_string(owned[k]) + ": boundary flag " + std::to_string(flag[k]) +
           ", but its triangles make it " + (mine ? "a boundary" : "an interior") + " vertex");
  }
  for (size_t i = 0; i < ghosts.size(); ++i) {
    if (ghost[i].boundary > 1)
      fail("vertex " + std::to_string(ghosts[i]) + ": boundary flag " +
           std::to_string(ghost[i].boundary) + " (0 or 1)");
    mesh->boundary[local_of(ghosts[i])] = ghost[i].boundary;
  }
  mesh->interior.clear();
  for (size_t l = 0; l < mesh->boundary.size(); ++l)
    if (!mesh->boundary[l]) mesh->interior.push_back(static_cast<int32_t>(l));
}

// The quality weights of the triangles here (from each corner's global row size, as
// GlobalQualityWeight computes them), the owned triangles, the neighbouring ranks and cut edges.
void WeighAndLink(const std::string& path, const std::vector<int64_t>& owned,
                  const std::vector<int64_t>& start, const std::vector<int64_t>& ghosts,
                  const std::vector<GhostRecord>& ghost, const SortedIds& local_index,
                  size_t triangles_here, RankNeighbourhood* out) {
  RankNeighbourhood& nb = *out;
  const int32_t rank = nb.rank;
  const int64_t n = nb.vertices;
  const size_t total = nb.gid.size();
  auto fail = [&](const std::string& what) { throw InputError(path, 0, what); };
  auto local_of = [&](int64_t g) { return static_cast<int32_t>(local_index.Find(g)); };
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
  for (size_t k = 0; k < owned.size(); ++k) row[local_of(owned[k])] = start[k + 1] - start[k];
  const double inv_v = 1.0 / static_cast<double>(n);
  nb.weight.resize(triangles_here);
  for (size_t t = 0; t < triangles_here; ++t) {
    const int32_t* c = &nb.mesh.tri[3 * t];
    nb.weight[t] = QualityWeightOf(inv_v, row[c[0]], row[c[1]], row[c[2]]);
    nb.owned_triangles += nb.part[std::min(c[0], std::min(c[1], c[2]))] == rank;
  }
  for (size_t k = 0; k < owned.size(); ++k) {
    const int32_t l = local_of(owned[k]);
    for (const int32_t* u = nb.mesh.v2v.RowBegin(l); u != nb.mesh.v2v.RowEnd(l); ++u)
      if (nb.part[*u] != rank) {
        nb.neighbours.push_back(nb.part[*u]);
        nb.cut_edges += nb.gid[*u] > owned[k];
      }
  }
  std::sort(nb.neighbours.begin(), nb.neighbours.end());
  nb.neighbours.erase(std::unique(nb.neighbours.begin(), nb.neighbours.end()), nb.neighbours.end());
}

RankNeighbourhood ReadNeighbourhood(MeshFile& f, int32_t rank, int32_t parts,
                                    std::vector<int64_t> owned, const GhostOwners& owners,
                                    const GhostLookup& lookup) {
  const std::string& path = f.path();
  const int64_t n = f.vertices(), nt = f.triangles();
  RankNeighbourhood nb;
  nb.rank = rank, nb.parts = parts, nb.vertices = n, nb.triangles = nt;
  nb.content_id = f.content_id();
  nb.owned = static_cast<int64_t>(owned.size());
  if (!owned.empty() && (owned.front() < 0 || owned.back() >= n))
    throw std::invalid_argument("ReadPartNeighbourhood: an owned id outside the mesh");
  const SortedIds own_index(owned);
  OwnedRows o = ReadOwnedRows(f, owned, own_index);
  nb.row_entries = o.start.back();
  const size_t triangles_here = o.tris.size();
  std::vector<int32_t>().swap(o.rows);  // the peak is the mesh built below: keep it lean
  std::vector<int64_t>().swap(o.tris);
  std::vector<int32_t>& corners = o.corners;

  // The vertices here: owned, and the ghosts (other corners), increasing global id. A run of
  // consecutive owned ids has no ghost inside it, so it keeps consecutive local ids.
  std::vector<int64_t> ghosts;
  for (int32_t c : corners)
    if (own_index.Find(c) < 0) ghosts.push_back(c);
  RadixSortUnique(&ghosts);
  nb.gid.resize(owned.size() + ghosts.size());
  std::merge(owned.begin(), owned.end(), ghosts.begin(), ghosts.end(), nb.gid.begin());
  const size_t total = nb.gid.size();
  const SortedIds local_index(nb.gid);
  auto local_of = [&](int64_t g) { return static_cast<int32_t>(local_index.Find(g)); };

  // The owned vertices' data, then the ghosts' from their owners (or the file).
  std::vector<int64_t> rf, re;  // runs of owned ids again (few)
  for (size_t k = 0; k < owned.size(); ++k)
    if (!k || owned[k] != owned[k - 1] + 1) {
      if (k) re.push_back(owned[k - 1] + 1);
      rf.push_back(owned[k]);
    }
  if (!owned.empty()) re.push_back(owned.back() + 1);
  std::vector<uint8_t> flag(owned.size());
  RawMesh raw;
  raw.vertex_file = raw.triangle_file = path;
  raw.xy.resize(2 * total);
  {
    std::vector<double> oxy(2 * owned.size());
    f.ReadRuns(MeshFile::kXy, rf, re, oxy.data());
    for (size_t k = 0; k < owned.size(); ++k) {
      const size_t l = static_cast<size_t>(local_of(owned[k]));
      raw.xy[2 * l] = oxy[2 * k], raw.xy[2 * l + 1] = oxy[2 * k + 1];
    }
  }
  f.ReadRuns(MeshFile::kBoundary, rf, re, flag.data());
  const OwnedLookup own = [&](int64_t g) {
    const int64_t k = own_index.Find(g);
    if (k < 0)
      throw InputError(path, 0,
                       "rank " + std::to_string(rank) + " was asked for vertex " +
                           std::to_string(g) + ", which it does not own");
    const size_t l = static_cast<size_t>(local_of(g));
    return GhostRecord{raw.xy[2 * l], raw.xy[2 * l + 1], o.start[k + 1] - o.start[k], flag[k]};
  };
  const std::vector<int32_t> ghost_owner = owners(ghosts);  // every rank calls it, ghosts or not
  if (ghost_owner.size() != ghosts.size())
    throw std::logic_error("ReadPartNeighbourhood: ghost owners of the wrong count");
  for (int32_t q : ghost_owner)
    if (q < 0 || q >= parts || q == rank)
      throw std::logic_error("ReadPartNeighbourhood: a ghost owned by this rank or none");
  std::vector<GhostRecord> ghost;
  if (lookup) {
    GhostRequest req{path, nb.content_id, n, ghosts, ghost_owner};
    ghost = lookup(req, own);
  } else {
    ghost = GhostsFromFile(f, ghosts);
  }
  if (ghost.size() != ghosts.size())
    throw std::logic_error("ReadPartNeighbourhood: a ghost lookup answered the wrong count");
  for (size_t i = 0; i < ghosts.size(); ++i) {
    const size_t l = static_cast<size_t>(local_of(ghosts[i]));
    raw.xy[2 * l] = ghost[i].x, raw.xy[2 * l + 1] = ghost[i].y;
  }
  raw.tri.resize(corners.size());
  for (size_t k = 0; k < corners.size(); ++k) raw.tri[k] = local_of(corners[k]);
  std::vector<int32_t>().swap(corners);
  for (int64_t g : nb.gid) raw.vertex_tag.Push(g);  // BuildMesh's messages name global ids
  BuildReport report;
  if (total > 0) nb.mesh = BuildMesh(std::move(raw), &report);  // else an empty part: no mesh
  if (!report.kept.empty())  // every vertex here is a corner of a triangle read
    throw std::logic_error(
        "ReadPartNeighbourhood: a vertex of the neighbourhood lies in no triangle");

  SetBoundaryFlags(path, owned, flag, ghosts, ghost, local_index, &nb.mesh);
  nb.part.assign(total, rank);
  for (size_t i = 0; i < ghosts.size(); ++i) nb.part[local_of(ghosts[i])] = ghost_owner[i];
  WeighAndLink(path, owned, o.start, ghosts, ghost, local_index, triangles_here, &nb);
  nb.bytes_read = f.bytes_read();
  return nb;
}

}  // namespace

RankNeighbourhood ReadRankNeighbourhood(const std::string& path, int32_t rank, int32_t parts,
                                        const GhostLookup& lookup) {
  MeshFile f(path);
  const int64_t n = f.vertices();
  CheckRanks(n, rank, parts);
  const GhostOwners owners = [&](const std::vector<int64_t>& ghosts) {
    std::vector<int32_t> q(ghosts.size());
    for (size_t i = 0; i < ghosts.size(); ++i) q[i] = RangeOwner(ghosts[i], n, parts);
    return q;
  };
  return ReadNeighbourhood(f, rank, parts, RangeIds(rank, n, parts), owners, lookup);
}

RankNeighbourhood ReadPartNeighbourhood(const std::string& path, int32_t rank, int32_t parts,
                                        std::vector<int64_t> owned, const GhostOwners& owners,
                                        const GhostLookup& lookup) {
  MeshFile f(path);
  CheckRanks(f.vertices(), rank, parts);
  return ReadNeighbourhood(f, rank, parts, std::move(owned), owners, lookup);
}

GraphRows RangeGraphRows(const Mesh& m, int32_t rank, int32_t parts) {
  const int64_t n = m.NumVertices();
  CheckRanks(n, rank, parts);
  GraphRows g;
  g.vertices = n, g.first = RangeFirst(rank, n, parts);
  const int64_t hi = RangeFirst(rank + 1, n, parts);
  for (int64_t v = g.first; v < hi; ++v) {
    const size_t a = g.adj.size();
    for (const int32_t* q = m.v2v.RowBegin(static_cast<int32_t>(v));
         q != m.v2v.RowEnd(static_cast<int32_t>(v)); ++q)
      g.adj.push_back(*q);
    std::sort(g.adj.begin() + static_cast<std::ptrdiff_t>(a), g.adj.end());
    g.off.push_back(static_cast<int64_t>(g.adj.size()));
  }
  return g;
}

GraphRows ReadRangeGraphRows(const std::string& path, int32_t rank, int32_t parts) {
  MeshFile f(path);
  const int64_t n = f.vertices();
  CheckRanks(n, rank, parts);
  const std::vector<int64_t> owned = RangeIds(rank, n, parts);
  const SortedIds index(owned);
  OwnedRows o = ReadOwnedRows(f, owned, index);
  GraphRows g;
  g.vertices = n, g.first = owned.empty() ? 0 : owned.front();
  g.bytes_read = f.bytes_read();
  // Two neighbours per (owned corner, triangle) pair, then each row sorted and made unique, in
  // place: the rows and triangle ids go first, so the peak is the pairs beside the corners.
  std::vector<int32_t>().swap(o.rows);
  std::vector<int64_t>().swap(o.tris);
  std::vector<int64_t> at(o.start.begin(), o.start.end() - 1), pair(2 * o.start.back());
  for (int64_t& a : at) a *= 2;
  for (size_t i = 0; i < o.corners.size(); i += 3)
    for (int j = 0; j < 3; ++j) {
      const int64_t k = index.Find(o.corners[i + j]);
      if (k < 0) continue;
      pair[at[k]++] = o.corners[i + (j + 1) % 3];
      pair[at[k]++] = o.corners[i + (j + 2) % 3];
    }
  std::vector<int64_t>().swap(at);
  std::vector<int32_t>().swap(o.corners);
  g.off.resize(owned.size() + 1);
  int64_t w = 0;
  for (size_t k = 0; k < owned.size(); ++k) {
    auto b = pair.begin() + 2 * o.start[k], e = pair.begin() + 2 * o.start[k + 1];
    std::sort(b, e);
    e = std::unique(b, e);
    const int64_t len = e - b;
    if (pair.begin() + w != b) std::copy(b, e, pair.begin() + w);  // w <= 2 start[k]: backwards
    g.off[k + 1] = w += len;
  }
  pair.resize(static_cast<size_t>(w));
  pair.shrink_to_fit();
  g.adj = std::move(pair);
  return g;
}

GhostLookup GhostExchange(Communicator& tx) {
  return [&tx](const GhostRequest& req, const OwnedLookup& mine) {
    const int32_t P = tx.size(), me = tx.rank();
    const std::vector<int64_t>& wanted = req.wanted;
    const std::vector<int32_t>& owner = req.owner;
    // The file's identity, then whom I ask and for how many: (rank, count) pairs by increasing
    // rank, all-gathered. Owners may come in any order (a scattered part's ghosts).
    std::vector<int64_t> per_owner(static_cast<size_t>(P));
    for (size_t i = 0; i < wanted.size(); ++i) {
      if (owner[i] == me || owner[i] < 0 || owner[i] >= P)
        throw std::logic_error("GhostExchange: a ghost owned by its own rank or none");
      ++per_owner[owner[i]];
    }
    std::vector<int64_t> need = {static_cast<int64_t>(req.content_id), req.vertices};
    for (int32_t q = 0; q < P; ++q)
      if (per_owner[q]) need.push_back(q), need.push_back(per_owner[q]);
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
      if (!request[q].empty()) tx.SendValues(q, request[q].data(), 8 * request[q].size());
    // Answers to whoever asked me, in rank order.
    for (int32_t p = 0; p < P; ++p) {
      const std::vector<int64_t>& pairs = asks[p];
      for (size_t k = 2; k < pairs.size(); k += 2) {
        if (pairs[k] != me) continue;
        std::vector<double> ids(static_cast<size_t>(pairs[k + 1]));
        tx.RecvValues(p, ids.data(), 8 * ids.size());
        std::vector<double>& a = answer[p];
        for (double id : ids) {
          const GhostRecord g = mine(static_cast<int64_t>(id));
          a.insert(a.end(),
                   {g.x, g.y, static_cast<double>(g.triangles), static_cast<double>(g.boundary)});
        }
        tx.SendValues(p, a.data(), 8 * a.size());
      }
    }
    // My answers, back in the order of `wanted`.
    std::vector<std::vector<size_t>> where(static_cast<size_t>(P));
    for (size_t i = 0; i < wanted.size(); ++i) where[owner[i]].push_back(i);
    std::vector<GhostRecord> out(wanted.size());
    for (int32_t q = 0; q < P; ++q) {
      if (request[q].empty()) continue;
      std::vector<double> a(4 * request[q].size());
      tx.RecvValues(q, a.data(), 8 * a.size());
      for (size_t k = 0; k < request[q].size(); ++k)
        out[where[q][k]] = {a[4 * k], a[4 * k + 1], static_cast<int64_t>(a[4 * k + 2]),
                            static_cast<uint8_t>(a[4 * k + 3])};
    }
    tx.Flush();
    return out;
  };
}

RankShare ShareOf(const RankNeighbourhood& nb) {
  return {nb.content_id,  nb.vertices,  nb.triangles, nb.owned_triangles,
          nb.row_entries, nb.cut_edges, nb.owned,     nb.neighbours};
}

std::string PackShare(const RankShare& s) {
  std::string b(sizeof(uint64_t) + 6 * sizeof(int64_t), '\0');
  char* p = &b[0];
  std::memcpy(p, &s.content_id, 8);
  const int64_t v[6] = {s.vertices,    s.triangles, s.owned_triangles,
                        s.row_entries, s.cut_edges, s.owned};
  std::memcpy(p + 8, v, sizeof v);
  b.append(reinterpret_cast<const char*>(s.neighbours.data()), 4 * s.neighbours.size());
  return b;
}

RankShare UnpackShare(const std::string& b) {
  if (b.size() < 56 || (b.size() - 56) % 4) throw std::logic_error("UnpackShare: bad size");
  RankShare s;
  int64_t v[6];
  std::memcpy(&s.content_id, b.data(), 8);
  std::memcpy(v, b.data() + 8, sizeof v);
  s.vertices = v[0], s.triangles = v[1], s.owned_triangles = v[2], s.row_entries = v[3];
  s.cut_edges = v[4], s.owned = v[5];
  s.neighbours.resize((b.size() - 56) / 4);
  if (!s.neighbours.empty()) std::memcpy(s.neighbours.data(), b.data() + 56, b.size() - 56);
  return s;
}

std::vector<std::vector<int32_t>> CheckRankShares(const std::string& path,
                                                  const std::vector<RankShare>& shares) {
  const int32_t parts = static_cast<int32_t>(shares.size());
  int64_t tris = 0, entries = 0, owned = 0;
  for (int32_t r = 0; r < parts; ++r) {
    const RankShare& s = shares[r];
    if (s.content_id != shares[0].content_id)
      throw InputError(path, 0,
                       "rank " + std::to_string(r) +
                           " read another mesh file than rank 0 (content "
                           "ids differ): every rank must see the same file");
    tris += s.owned_triangles, entries += s.row_entries, owned += s.owned;
  }
  const int64_t nv = parts ? shares[0].vertices : 0;
  if (owned != nv)
    throw InputError(path, 0,
                     "the ranks own " + std::to_string(owned) + " vertices, the header says " +
                         std::to_string(nv) + " (a partition that leaves out or repeats one)");
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
