// Permutation and ApplyPermutation; see permutation.h. Applying costs O(V + T): a counting sort of
// the triangles by smallest new corner, then every array permuted in place of a rebuild (the
// rebuild, ApplyPermutationByRebuild, stays as the tests' reference).
#include "core/permutation.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

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
  throw std::invalid_argument("unknown triangle order '" + s + "' (sorted or file)");
}

const char* TriangleOrderName(TriangleOrder t) {
  return t == TriangleOrder::kFile ? "file" : "sorted";
}

namespace {

// new triangle id of each old triangle: the identity for kFile, else a stable counting sort by the
// smallest new corner.
std::vector<int32_t> TriangleNewIds(const Mesh& m, const Permutation& p, TriangleOrder order) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  std::vector<int32_t> newt(nt);
  if (order == TriangleOrder::kFile) {
    for (int32_t t = 0; t < nt; ++t) newt[t] = t;
    return newt;
  }
  std::vector<int64_t> start(static_cast<size_t>(nv) + 1, 0);
  for (int32_t t = 0; t < nt; ++t) {
    const int32_t* c = &m.tri[3 * int64_t{t}];
    newt[t] = std::min({p.NewOf(c[0]), p.NewOf(c[1]), p.NewOf(c[2])});  // the key, for now
    ++start[newt[t] + 1];
  }
  for (int32_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  for (int32_t t = 0; t < nt; ++t) newt[t] = static_cast<int32_t>(start[newt[t]]++);
  return newt;
}

// Row i of the result = row p.OldOf(i) of `in`, each entry mapped through `map` and the row sorted.
void PermuteCsr(const Csr& in, const Permutation& p, const int32_t* map, Csr* out) {
  const int32_t n = p.size();
  out->off.assign(static_cast<size_t>(n) + 1, 0);
  for (int32_t i = 0; i < n; ++i) out->off[i + 1] = out->off[i] + in.RowSize(p.OldOf(i));
  out->idx.resize(in.idx.size());
#pragma omp parallel for schedule(static, 4096)
  for (int32_t i = 0; i < n; ++i) {
    const int32_t o = p.OldOf(i);
    int32_t* dst = out->idx.data() + out->off[i];
    const int64_t k = in.RowSize(o);
    for (int64_t j = 0; j < k; ++j) {  // insertion: rows hold a handful of entries
      const int32_t v = map[in.idx[in.off[o] + j]];
      int64_t q = j;
      for (; q > 0 && dst[q - 1] > v; --q) dst[q] = dst[q - 1];
      dst[q] = v;
    }
  }
}

}  // namespace

Mesh ApplyPermutation(const Mesh& m, const Permutation& p, TriangleOrder order) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  if (p.size() != nv)
    throw std::invalid_argument("the permutation has " + std::to_string(p.size()) +
                                " entries, the mesh " + std::to_string(nv) + " vertices");
  Mesh r;
  r.xy.resize(m.xy.size());
  r.boundary.resize(m.boundary.size());
#pragma omp parallel for schedule(static, 4096)
  for (int32_t i = 0; i < nv; ++i) {
    const int32_t o = p.OldOf(i);
    r.xy[2 * int64_t{i}] = m.xy[2 * int64_t{o}];
    r.xy[2 * int64_t{i} + 1] = m.xy[2 * int64_t{o} + 1];
    r.boundary[i] = m.boundary[o];
  }
  const std::vector<int32_t> newt = TriangleNewIds(m, p, order);
  r.tri.resize(m.tri.size());
#pragma omp parallel for schedule(static, 4096)
  for (int32_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      r.tri[3 * int64_t{newt[t]} + k] = p.NewOf(m.tri[3 * int64_t{t} + k]);
  PermuteCsr(m.v2v, p, p.old_to_new().data(), &r.v2v);
  PermuteCsr(m.v2t, p, newt.data(), &r.v2t);
  r.interior.reserve(m.interior.size());
  for (int32_t i = 0; i < nv; ++i)
    if (!r.boundary[i]) r.interior.push_back(i);
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
  std::vector<int64_t> span;
  span.reserve(m.v2v.idx.size() / 2);
  for (int32_t v = 0; v < m.NumVertices(); ++v)
    for (const int32_t* q = m.v2v.RowBegin(v); q != m.v2v.RowEnd(v); ++q)
      if (*q > v) span.push_back(std::abs(int64_t{p.NewOf(v)} - p.NewOf(*q)));
  EdgeSpan e;
  if (span.empty()) return e;
  double sum = 0;
  for (int64_t s : span) sum += static_cast<double>(s);
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
