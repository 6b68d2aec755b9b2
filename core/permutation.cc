// Permutation and ApplyPermutation; see permutation.h. Applying costs O(V + T) and runs in
// parallel: every array is permuted in place of a rebuild (the rebuild, ApplyPermutationByRebuild,
// stays as the tests' reference), with parallel scans for the offsets, so nothing is serial but a
// sum per thread. Written into reused arrays, nothing is allocated or zeroed.
#include "core/permutation.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "core/error.h"

namespace meshreuse {

Permutation Permutation::Clone() const {
  Permutation p;
  p.new_to_old_ = new_to_old_;
  p.old_to_new_ = old_to_new_;
  return p;
}

Permutation Permutation::FromNewToOld(std::vector<int32_t> new_to_old) {
  const int64_t n = static_cast<int64_t>(new_to_old.size());
  if (n > INT32_MAX) throw std::invalid_argument("permutation too large for 32-bit ids");
  Permutation p;
  p.old_to_new_.assign(n, -1);
  for (int64_t i = 0; i < n; ++i) {
    const int32_t o = new_to_old[i];
    if (o < 0 || o >= n)
      throw std::invalid_argument("position " + std::to_string(i) + " holds id " +
                                  std::to_string(o) + ", outside 0.." + std::to_string(n - 1));
    if (p.old_to_new_[o] >= 0)
      throw std::invalid_argument("id " + std::to_string(o) + " appears at positions " +
                                  std::to_string(p.old_to_new_[o]) + " and " + std::to_string(i));
    p.old_to_new_[o] = static_cast<int32_t>(i);
  }
  p.new_to_old_ = std::move(new_to_old);
  return p;
}

Permutation Permutation::Identity(int32_t n) {
  std::vector<int32_t> id(n);
  for (int32_t i = 0; i < n; ++i) id[i] = i;
  return FromNewToOld(std::move(id));
}

Permutation Permutation::Inverse() const {
  Permutation p;
  p.new_to_old_ = old_to_new_;
  p.old_to_new_ = new_to_old_;
  return p;
}

TriangleOrder ParseTriangleOrder(const std::string& s) {
  if (s == "sorted") return TriangleOrder::kSorted;
  if (s == "file") return TriangleOrder::kFile;
  throw UsageError("unknown triangle order '" + s + "' (sorted or file)");
}

const char* TriangleOrderName(TriangleOrder t) {
  return t == TriangleOrder::kFile ? "file" : "sorted";
}

namespace {

// A parallel two-pass scan over [0, n) cut into one block per thread: count(b, e) says how much
// block [b, e) holds, the totals are added up serially (one per thread), then fill(b, e, start)
// runs with the block's start. Returns the total (after every fill).
template <class Count, class Fill>
int64_t BlockScan(int64_t n, Count count, Fill fill) {
  const int threads = omp_get_max_threads();
  std::vector<int64_t> block(static_cast<size_t>(threads) + 1, 0);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int64_t b = n * t / nt, e = n * (t + 1) / nt;
    block[t + 1] = count(b, e);
#pragma omp barrier
#pragma omp single
    for (int k = 0; k < nt; ++k) block[k + 1] += block[k];
    fill(b, e, block[t]);
  }
  return block.back();
}

// a[i] += a[0] + ... + a[i - 1] for i < n, in parallel.
template <class T>
void InclusiveScan(T* a, int64_t n) {
  BlockScan(
      n,
      [&](int64_t b, int64_t e) {
        int64_t s = 0;
        for (int64_t i = b; i < e; ++i) s += a[i];
        return s;
      },
      [&](int64_t b, int64_t e, int64_t start) {
        T s = static_cast<T>(start);
        for (int64_t i = b; i < e; ++i) a[i] = s += a[i];
      });
}

constexpr int64_t kRankSortMax = 32;

// The scattered loops below touch one far line per item. Rows end at unpredictable counts, and
// each mispredicted end discards the loads in flight behind it, so the hardware keeps few misses
// outstanding; a prefetch kAhead items early survives that and keeps the memory system busy
// (measured: a quarter off the apply at 10^7 vertices).
constexpr int32_t kAhead = 64;
inline int32_t NewAhead(const Permutation& p, int32_t o) {
  return p.NewOf(o + kAhead < p.size() ? o + kAhead : o);
}

// Row p.NewOf(o) of `out` = row o of `in`, each entry mapped through `map` and the row sorted;
// out->off already holds the offsets. Pushed from the old rows, in their order: the reads follow
// the source mesh's own locality and only the writes land far apart (stores do not stall the
// core as dependent loads do).
void PermuteRows(const Csr& in, const Permutation& p, const int32_t* map, Csr* out) {
  const int32_t n = p.size();
  out->idx.resize(in.idx.size());
#pragma omp parallel for schedule(static, 4096)
  for (int32_t o = 0; o < n; ++o) {
    __builtin_prefetch(&out->off[NewAhead(p, o)]);
    if (o + kAhead / 2 < n)
      __builtin_prefetch(out->idx.data() + out->off[p.NewOf(o + kAhead / 2)], 1);
    int32_t* dst = out->idx.data() + out->off[p.NewOf(o)];
    const int32_t* src = in.RowBegin(o);
    const int64_t k = in.RowSize(o);
    if (k > kRankSortMax) {  // rare: a vertex of very high degree
      for (int64_t j = 0; j < k; ++j) dst[j] = map[src[j]];
      std::sort(dst, dst + k);
      continue;
    }
    // Rows hold a handful of distinct entries: each goes to its rank (how many are smaller),
    // counted without branches, where an insertion sort would mispredict.
    int32_t v[kRankSortMax];
    if (k <= 8) {  // the common case, padded to a fixed 8 so the counts vectorise
      for (int j = 0; j < 8; ++j) v[j] = j < k ? map[src[j]] : INT32_MAX;
      for (int64_t j = 0; j < k; ++j) {
        int32_t rank = 0;
        for (int l = 0; l < 8; ++l) rank += v[l] < v[j];
        dst[rank] = v[j];
      }
      continue;
    }
    for (int64_t j = 0; j < k; ++j) v[j] = map[src[j]];
    for (int64_t j = 0; j < k; ++j) {
      int64_t rank = 0;
      for (int64_t l = 0; l < k; ++l) rank += v[l] < v[j];
      dst[rank] = v[j];
    }
  }
}

// New triangle ids. kFile: the identity. kSorted: stably by smallest new corner (the key). The
// triangles whose key is NewOf(o) are in row o of v2t, in increasing old id: counting them per
// vertex, a scan in new order and each triangle's rank among its key's give the stable sort in
// parallel.
AlignedVector<int32_t> NewTriangleIds(const Mesh& m, const Permutation& p, TriangleOrder order) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  AlignedVector<int32_t> newt(static_cast<size_t>(nt));
  if (order == TriangleOrder::kFile) {
#pragma omp parallel for schedule(static, 4096)
    for (int32_t t = 0; t < nt; ++t) newt[t] = t;
    return newt;
  }
  AlignedVector<int32_t> key(static_cast<size_t>(nt));
#pragma omp parallel for schedule(static, 4096)
  for (int32_t t = 0; t < nt; ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    key[t] = std::min({p.NewOf(c[0]), p.NewOf(c[1]), p.NewOf(c[2])});
  }
  // Per triangle its rank among the triangles of its key (their order in the key's old row): one
  // byte, written where it is counted, so the placement needs no second pass over the rows.
  AlignedVector<int32_t> start(static_cast<size_t>(nv) + 1);  // nt < 2^31
  AlignedVector<uint8_t> rank(static_cast<size_t>(nt));
  start[0] = 0;
  bool wide = false;  // some vertex is the key of 255 triangles or more (a huge fan)
#pragma omp parallel for schedule(static, 4096) reduction(|| : wide)
  for (int32_t o = 0; o < nv; ++o) {
    __builtin_prefetch(&start[NewAhead(p, o) + 1], 1);
    const int32_t i = p.NewOf(o);
    int32_t k = 0;
    for (const int32_t* q = m.v2t.RowBegin(o); q != m.v2t.RowEnd(o); ++q)
      if (key[*q] == i) rank[*q] = static_cast<uint8_t>(k < 255 ? k++ : (wide = true, k++));
    start[i + 1] = k;
  }
  InclusiveScan(start.data() + 1, nv);
  if (wide) {  // ranks did not fit a byte: place from the rows instead
#pragma omp parallel for schedule(static, 4096)
    for (int32_t o = 0; o < nv; ++o) {
      const int32_t i = p.NewOf(o);
      int32_t s = start[i];
      for (const int32_t* q = m.v2t.RowBegin(o); q != m.v2t.RowEnd(o); ++q)
        if (key[*q] == i) newt[*q] = s++;
    }
  } else {
#pragma omp parallel for schedule(static, 4096)
    for (int32_t t = 0; t < nt; ++t) {
      if (t + kAhead < nt) __builtin_prefetch(&start[key[t + kAhead]]);
      newt[t] = start[key[t]] + rank[t];
    }
  }
  return newt;
}

// The renumbered corners in old triangle order: sequential reads, scattered stores.
void PermuteTriangles(const Mesh& m, const Permutation& p, const AlignedVector<int32_t>& newt,
                      AlignedVector<int32_t>* tri) {
  const int32_t nt = m.NumTriangles();
  tri->resize(m.tri.size());
#pragma omp parallel for schedule(static, 4096)
  for (int32_t t = 0; t < nt; ++t) {
    if (t + kAhead < nt) __builtin_prefetch(&(*tri)[3 * int64_t{newt[t + kAhead]}], 1);
    const int32_t* c = &m.tri[3 * int64_t{t}];
    int32_t* d = &(*tri)[3 * int64_t{newt[t]}];
    d[0] = p.NewOf(c[0]), d[1] = p.NewOf(c[1]), d[2] = p.NewOf(c[2]);
  }
}

// Row offsets of `in` laid out in new order: sizes scattered to their new rows, then a scan.
void PermuteOffsets(const Csr& in, const Permutation& p, AlignedVector<int64_t>* off) {
  const int32_t n = p.size();
  off->resize(static_cast<size_t>(n) + 1);
  (*off)[0] = 0;
#pragma omp parallel for schedule(static, 4096)
  for (int32_t o = 0; o < n; ++o) {
    __builtin_prefetch(&(*off)[NewAhead(p, o) + 1], 1);
    (*off)[p.NewOf(o) + 1] = in.RowSize(o);
  }
  InclusiveScan(off->data() + 1, n);
}

// Non-boundary vertices in increasing id: count per block, scan, fill.
void InteriorOf(const std::vector<uint8_t>& boundary, AlignedVector<int32_t>* interior) {
  int64_t n_interior = 0;
  for (uint8_t f : boundary) n_interior += !f;
  interior->resize(static_cast<size_t>(n_interior));
  BlockScan(
      static_cast<int64_t>(boundary.size()),
      [&](int64_t b, int64_t e) {
        int64_t s = 0;
        for (int64_t i = b; i < e; ++i) s += !boundary[i];
        return s;
      },
      [&](int64_t b, int64_t e, int64_t start) {
        int32_t* out = interior->data() + start;
        for (int64_t i = b; i < e; ++i)
          if (!boundary[i]) *out++ = static_cast<int32_t>(i);
      });
}

void CheckSizes(const Mesh& m, const Permutation& p) {
  if (p.size() != m.NumVertices())
    throw std::invalid_argument("the permutation has " + std::to_string(p.size()) +
                                " entries, the mesh " + std::to_string(m.NumVertices()) +
                                " vertices");
}

}  // namespace

void ApplyPermutationInto(const Mesh& m, const Permutation& p, TriangleOrder order, Mesh* r) {
  CheckSizes(m, p);
  if (r == &m) throw std::invalid_argument("ApplyPermutationInto: the target is the source");
  const int32_t nv = m.NumVertices();
  // One pass over the old vertices: coordinates, flags and both adjacencies' row sizes.
  r->xy.resize(m.xy.size());
  r->boundary.resize(m.boundary.size());
  r->v2v.off.resize(static_cast<size_t>(nv) + 1);
  r->v2t.off.resize(static_cast<size_t>(nv) + 1);
  r->v2v.off[0] = r->v2t.off[0] = 0;
#pragma omp parallel for schedule(static, 4096)
  for (int32_t o = 0; o < nv; ++o) {
    const int32_t i = p.NewOf(o), a = NewAhead(p, o);
    __builtin_prefetch(&r->xy[2 * int64_t{a}], 1);
    __builtin_prefetch(&r->boundary[a], 1);
    __builtin_prefetch(&r->v2v.off[a + 1], 1);
    __builtin_prefetch(&r->v2t.off[a + 1], 1);
    r->xy[2 * int64_t{i}] = m.xy[2 * int64_t{o}];
    r->xy[2 * int64_t{i} + 1] = m.xy[2 * int64_t{o} + 1];
    r->boundary[i] = m.boundary[o];
    r->v2v.off[i + 1] = m.v2v.RowSize(o);
    r->v2t.off[i + 1] = m.v2t.RowSize(o);
  }
  InclusiveScan(r->v2v.off.data() + 1, nv);
  InclusiveScan(r->v2t.off.data() + 1, nv);
  const AlignedVector<int32_t> newt = NewTriangleIds(m, p, order);
  PermuteTriangles(m, p, newt, &r->tri);
  PermuteRows(m.v2v, p, p.old_to_new().data(), &r->v2v);
  PermuteRows(m.v2t, p, newt.data(), &r->v2t);
  InteriorOf(r->boundary, &r->interior);
}

void ApplyPermutationInPlace(Mesh* m, const Permutation& p, TriangleOrder order) {
  CheckSizes(*m, p);
  const int32_t nv = m->NumVertices();
  // Array by array, each new one built from the old mesh and swapped in, the old one freed: the
  // peak is the mesh plus its largest array plus the triangle ids.
  AlignedVector<int32_t> newt = NewTriangleIds(*m, p, order);
  {
    AlignedVector<int32_t> tri;
    PermuteTriangles(*m, p, newt, &tri);
    m->tri.swap(tri);
  }
  for (int pass = 0; pass < 2; ++pass) {  // v2v, then v2t (which needs newt)
    Csr& in = pass == 0 ? m->v2v : m->v2t;
    Csr c;
    PermuteOffsets(in, p, &c.off);
    PermuteRows(in, p, pass == 0 ? p.old_to_new().data() : newt.data(), &c);
    in = std::move(c);
  }
  newt = AlignedVector<int32_t>();
  {
    AlignedVector<double> xy(m->xy.size());
#pragma omp parallel for schedule(static, 4096)
    for (int32_t o = 0; o < nv; ++o) {
      __builtin_prefetch(&xy[2 * int64_t{NewAhead(p, o)}], 1);
      xy[2 * int64_t{p.NewOf(o)}] = m->xy[2 * int64_t{o}];
      xy[2 * int64_t{p.NewOf(o)} + 1] = m->xy[2 * int64_t{o} + 1];
    }
    m->xy.swap(xy);
  }
  {
    std::vector<uint8_t> boundary(m->boundary.size());
#pragma omp parallel for schedule(static, 4096)
    for (int32_t o = 0; o < nv; ++o) boundary[p.NewOf(o)] = m->boundary[o];
    m->boundary.swap(boundary);
  }
  InteriorOf(m->boundary, &m->interior);
}

Mesh ApplyPermutation(const Mesh& m, const Permutation& p, TriangleOrder order) {
  Mesh r;
  ApplyPermutationInto(m, p, order, &r);
  return r;
}

Mesh ApplyPermutationByRebuild(const Mesh& m, const Permutation& p, TriangleOrder order) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  if (p.size() != nv)
    throw std::invalid_argument("the permutation has " + std::to_string(p.size()) +
                                " entries, the mesh " + std::to_string(nv) + " vertices");
  RawMesh raw;
  raw.vertex_file = raw.triangle_file = "<reordered>";
  raw.xy.resize(2 * static_cast<size_t>(nv));
  for (int32_t i = 0; i < nv; ++i) {
    raw.xy[2 * int64_t{i}] = m.xy[2 * int64_t{p.OldOf(i)}];
    raw.xy[2 * int64_t{i} + 1] = m.xy[2 * int64_t{p.OldOf(i)} + 1];
  }
  if (order == TriangleOrder::kFile) {
    raw.tri.resize(m.tri.size());
    for (size_t i = 0; i < m.tri.size(); ++i) raw.tri[i] = p.NewOf(m.tri[i]);
    return BuildMesh(std::move(raw));
  }
  // Counting sort of triangles by smallest new corner; ties keep the old triangle order.
  std::vector<int64_t> start(static_cast<size_t>(nv) + 1, 0);
  std::vector<int32_t> key(nt);
  for (int32_t t = 0; t < nt; ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    key[t] = std::min({p.NewOf(c[0]), p.NewOf(c[1]), p.NewOf(c[2])});
    ++start[key[t] + 1];
  }
  for (int32_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  raw.tri.resize(m.tri.size());
  for (int32_t t = 0; t < nt; ++t) {
    const int64_t pos = start[key[t]]++;
    for (int k = 0; k < 3; ++k) raw.tri[3 * pos + k] = p.NewOf(m.tri[3 * int64_t{t} + k]);
  }
  return BuildMesh(std::move(raw));
}

EdgeSpan MeasureEdgeSpan(const Mesh& m, const Permutation& p) {
  std::vector<int32_t> span;  // < 2^31: both ends are 32-bit ids >= 0
  span.reserve(m.v2v.idx.size() / 2);
  for (int32_t v = 0; v < m.NumVertices(); ++v)
    for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
      if (*q > v) span.push_back(std::abs(p.NewOf(v) - p.NewOf(*q)));
  EdgeSpan e;
  if (span.empty()) return e;
  double sum = 0;
  for (int32_t s : span) sum += static_cast<double>(s);
  e.mean = sum / static_cast<double>(span.size());
  // Quantile X: the smallest span with at least a fraction X of the edges at or below it.
  auto quantile = [&](double x) {
    const size_t k = static_cast<size_t>(std::ceil(x * static_cast<double>(span.size()))) - 1;
    std::nth_element(span.begin(), span.begin() + k, span.end());
    return span[k];
  };
  e.median = quantile(0.5);
  e.p90 = quantile(0.9);
  e.p99 = quantile(0.99);
  e.max = *std::max_element(span.begin(), span.end());
  return e;
}

}  // namespace meshreuse
