// Kernel/NAME: each kernel of the registry (core/kernels/, its template on NullSink: the timed
// loop) against a sweep written here by hand from the kernel's definition, with no sink at all,
// alternated run by run: ms per sweep (sweeps 2.., median) and their ratio pair by pair (issue
// 41's goal: the registry's loop within 2% of the hand-written one, i.e. the sink compiles away).
// Both start from the same mesh and run the same sweeps; the hand-written sweep's measure must
// equal the kernel's (else the benchmark stops with an error: it would not be the same work). The
// hand-written loops read their bound from memory at each test, as every kernel's documented
// access sequence does (core/smoother.h ForStatic's volatile end, which the trace reports): the
// comparison is then of the sink alone.
// laplacian's own comparison is Sweep/plain against Sweep/null (bench_main.cc).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/aligned.h"
#include "core/kernels/edge_swap.h"
#include "core/kernels/kernel.h"
#include "core/kernels/stiffness.h"
#include "core/kernels/untangle.h"
#include "core/quality.h"
#include "core/smoother.h"
#include "tests/bench/bench_util.h"

namespace meshreuse {
namespace {

double Area2(double px, double py, double bx, double by, double cx, double cy) {
  return (bx - px) * (cy - py) - (by - py) * (cx - px);
}

// A sweep written by hand: Start prepares its state from the mesh (untimed, as the kernel's own
// set-up is), Sweep runs one and answers the kernel's measure after it.
struct Hand {
  virtual ~Hand() = default;
  virtual void Start(const Mesh& base) = 0;
  virtual double Sweep() = 0;
};

// Its arrays as the kernel's are (64-byte aligned, made per run): the same placement in memory.
struct HandSpmv : Hand {
  StiffnessMatrix a;
  AlignedVector<double> x, y;
  void Start(const Mesh& base) override {
    a = StiffnessPattern(base);
    NullSink none;
    AssembleStiffness(base, a, none);
    x.resize(static_cast<size_t>(base.NumVertices())), y.assign(x.size(), 0.0);
    for (size_t i = 0; i < x.size(); ++i) x[i] = base.xy[2 * i];
  }
  double Sweep() override {
    double e = 0.0;
    volatile const size_t n = x.size();  // the loop bound read at each test, as the kernel's
    for (size_t i = 0; i < n; ++i) {
      double s = 0.0;
      for (int64_t j = a.off[i]; j < a.off[i + 1]; ++j) s += a.val[j] * x[a.col[j]];
      y[i] = s;
      e += s * x[i];
    }
    return e;
  }
};

struct HandAssembly : Hand {
  const Mesh* m = nullptr;
  StiffnessMatrix a;
  void Start(const Mesh& base) override { m = &base, a = StiffnessPattern(base); }
  double Sweep() override {
    std::fill(a.val.begin(), a.val.end(), 0.0);
    double e = 0.0;
    volatile const int32_t n = m->NumTriangles();  // the bound read at each test, as the kernel's
    for (int32_t t = 0; t < n; ++t) {
      const int32_t* c = &m->tri[3 * int64_t{t}];
      const double* p = &m->xy[2 * int64_t{c[0]}];
      const double* q = &m->xy[2 * int64_t{c[1]}];
      const double* r = &m->xy[2 * int64_t{c[2]}];
      double k[9];
      LocalStiffness(p[0], p[1], q[0], q[1], r[0], r[1], k);
      for (int j = 0; j < 9; ++j) a.val[a.map[9 * int64_t{t} + j]] += k[j];
      e += k[0] + k[4] + k[8];
    }
    return e;
  }
};

// The smoothing kernels' state: the global quality kept from per-triangle weights and qualities.
struct HandSmoothing : Hand {
  Mesh m;
  std::vector<double> w, tq;
  double q = 0.0;
  void Start(const Mesh& base) override {
    m = base.Clone();
    w.clear(), tq.clear(), q = 0.0;
    for (int32_t t = 0; t < m.NumTriangles(); ++t) {
      w.push_back(GlobalQualityWeight(m, t));
      tq.push_back(TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{t}]));
      q += w.back() * tq.back();
    }
  }
  // After v moved: its triangles' qualities anew, the global quality's change.
  void Requalify(int32_t v) {
    for (int64_t i = m.v2t.off[v]; i < m.v2t.off[v + 1]; ++i) {
      const int32_t t = m.v2t.idx[i];
      const double nq = TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{t}]);
      q += w[t] * (nq - tq[t]);
      tq[t] = nq;
    }
  }
};

// smart-laplacian: the neighbours' average, kept when the least quality of v's triangles does not
// drop (core/kernels/smart_laplacian.cc).
struct HandSmart : HandSmoothing {
  double Sweep() override {
    const int32_t* volatile end = m.interior.data() + m.interior.size();  // as the kernel's bound
    for (const int32_t* it = m.interior.data(); it < end; ++it) {
      const int32_t v = *it;
      double sx = 0.0, sy = 0.0;
      for (int64_t i = m.v2v.off[v]; i < m.v2v.off[v + 1]; ++i) {
        const int32_t u = m.v2v.idx[i];
        sx += m.xy[2 * int64_t{u}], sy += m.xy[2 * int64_t{u} + 1];
      }
      const double inv = 1.0 / static_cast<double>(m.v2v.off[v + 1] - m.v2v.off[v]);
      const double x = sx * inv, y = sy * inv;
      double old_min = 1.0, new_min = 1.0;
      for (int64_t i = m.v2t.off[v]; i < m.v2t.off[v + 1]; ++i) {
        const int32_t t = m.v2t.idx[i];
        const int32_t* c = &m.tri[3 * int64_t{t}];
        double p[6];
        for (int j = 0; j < 3; ++j) {
          p[2 * j] = c[j] == v ? x : m.xy[2 * int64_t{c[j]}];
          p[2 * j + 1] = c[j] == v ? y : m.xy[2 * int64_t{c[j]} + 1];
        }
        old_min = std::min(old_min, tq[t]);
        new_min = std::min(new_min, TriangleQuality(p[0], p[1], p[2], p[3], p[4], p[5]));
      }
      if (!(new_min >= old_min)) continue;
      m.xy[2 * int64_t{v}] = x, m.xy[2 * int64_t{v} + 1] = y;
      Requalify(v);
    }
    return q;
  }
};

// A vertex's other two corners per triangle, in the triangle's cyclic order after it.
struct Corners {
  int n = 0;
  double bx[64], by[64], cx[64], cy[64];
  int32_t t[64];
  bool Gather(const Mesh& m, int32_t v) {
    n = static_cast<int>(m.v2t.off[v + 1] - m.v2t.off[v]);
    if (n > 64) return false;
    for (int k = 0; k < n; ++k) {
      t[k] = m.v2t.idx[m.v2t.off[v] + k];
      const int32_t* c = &m.tri[3 * int64_t{t[k]}];
      const int j = c[0] == v ? 0 : c[1] == v ? 1 : 2;
      const double* b = &m.xy[2 * int64_t{c[(j + 1) % 3]}];
      const double* d = &m.xy[2 * int64_t{c[(j + 2) % 3]}];
      bx[k] = b[0], by[k] = b[1], cx[k] = d[0], cy[k] = d[1];
    }
    return true;
  }
};

// local-opt: two Armijo steepest-descent steps on the sum of inverse mean ratios
// (core/kernels/local_opt.cc).
struct HandLocalOpt : HandSmoothing {
  static double F(const Corners& p, const double* s, double x, double y, double* gx, double* gy) {
    static const double k = 2.0 * std::sqrt(3.0);
    double f = 0.0, ax = 0.0, ay = 0.0;
    for (int i = 0; i < p.n; ++i) {
      const double bx = p.bx[i], by = p.by[i], cx = p.cx[i], cy = p.cy[i];
      const double a2 = s[i] * Area2(x, y, bx, by, cx, cy);
      if (!(a2 > 0.0)) return INFINITY;
      const double sq = (x - bx) * (x - bx) + (y - by) * (y - by) + (bx - cx) * (bx - cx) +
                        (by - cy) * (by - cy) + (cx - x) * (cx - x) + (cy - y) * (cy - y);
      f += sq / (k * a2);
      const double dsx = 2.0 * (x - bx) + 2.0 * (x - cx), dsy = 2.0 * (y - by) + 2.0 * (y - cy);
      const double dax = s[i] * (by - cy), day = s[i] * (cx - bx);
      ax += (dsx * a2 - sq * dax) / (k * a2 * a2);
      ay += (dsy * a2 - sq * day) / (k * a2 * a2);
    }
    if (gx) *gx = ax, *gy = ay;
    return f;
  }
  double Sweep() override {
    Corners p;
    const int32_t* volatile end = m.interior.data() + m.interior.size();  // as the kernel's bound
    for (const int32_t* it = m.interior.data(); it < end; ++it) {
      const int32_t v = *it;
      if (!p.Gather(m, v) || p.n == 0) continue;
      const double x0 = m.xy[2 * int64_t{v}], y0 = m.xy[2 * int64_t{v} + 1];
      double s[64], l2 = 0.0;
      for (int i = 0; i < p.n; ++i) {
        s[i] = Area2(x0, y0, p.bx[i], p.by[i], p.cx[i], p.cy[i]) >= 0.0 ? 1.0 : -1.0;
        l2 += (x0 - p.bx[i]) * (x0 - p.bx[i]) + (y0 - p.by[i]) * (y0 - p.by[i]);
      }
      l2 /= p.n;
      double px = x0, py = y0, gx = 0.0, gy = 0.0;
      double f = F(p, s, px, py, &gx, &gy);
      if (!std::isfinite(f)) continue;
      bool moved = false;
      for (int step = 0; step < 2; ++step) {
        const double g2 = gx * gx + gy * gy;
        if (!(g2 > 0.0)) break;
        double alpha = l2, nx = px, ny = py;
        int h = 0;
        for (; h <= 10; ++h, alpha *= 0.5) {
          nx = px - alpha * gx, ny = py - alpha * gy;
          if (F(p, s, nx, ny, nullptr, nullptr) <= f - 1e-4 * alpha * g2) break;
        }
        if (h > 10) break;
        px = nx, py = ny, moved = true;
        f = F(p, s, px, py, &gx, &gy);
      }
      if (!moved) continue;
      m.xy[2 * int64_t{v}] = px, m.xy[2 * int64_t{v} + 1] = py;
      for (int k = 0; k < p.n; ++k) {
        const double nq = TriangleQuality(px, py, p.bx[k], p.by[k], p.cx[k], p.cy[k]);
        q += w[p.t[k]] * (nq - tq[p.t[k]]);
        tq[p.t[k]] = nq;
      }
    }
    return q;
  }
};

// untangle: one damped Newton step per vertex on sum max(0, beta - o Area2)^2, the inverted
// count kept (core/kernels/untangle.cc).
struct HandUntangle : Hand {
  Mesh m;
  TangleStats ts;
  int64_t inverted = 0;
  double F(const Corners& p, double x, double y) const {
    double f = 0.0;
    for (int i = 0; i < p.n; ++i) {
      const double d = ts.beta - ts.orientation * Area2(x, y, p.bx[i], p.by[i], p.cx[i], p.cy[i]);
      if (d > 0.0) f += d * d;
    }
    return f;
  }
  // Turned-over triangles of v's patch with v at (x, y), each area from its stored corner order.
  int Inverted(int32_t v, const Corners& p, double x, double y) const {
    int n = 0;
    for (int k = 0; k < p.n; ++k) {
      const int32_t* c = &m.tri[3 * int64_t{p.t[k]}];
      double q[6];
      for (int j = 0; j < 3; ++j) {
        q[2 * j] = c[j] == v ? x : m.xy[2 * int64_t{c[j]}];
        q[2 * j + 1] = c[j] == v ? y : m.xy[2 * int64_t{c[j]} + 1];
      }
      n += !(ts.orientation * Area2(q[0], q[1], q[2], q[3], q[4], q[5]) > 0.0);
    }
    return n;
  }
  void Start(const Mesh& base) override {
    m = base.Clone();
    ts = TangleMesh(m, kTangleShare, kTangleSeed);
    inverted = ts.inverted;
  }
  double Sweep() override {
    const double o = ts.orientation;
    Corners p;
    const int32_t* volatile end = m.interior.data() + m.interior.size();  // as the kernel's bound
    for (const int32_t* it = m.interior.data(); it < end; ++it) {
      const int32_t v = *it;
      if (!p.Gather(m, v)) continue;
      const double px = m.xy[2 * int64_t{v}], py = m.xy[2 * int64_t{v} + 1];
      double gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0;
      for (int i = 0; i < p.n; ++i) {
        const double d = ts.beta - o * Area2(px, py, p.bx[i], p.by[i], p.cx[i], p.cy[i]);
        if (!(d > 0.0)) continue;
        const double ax = o * (p.by[i] - p.cy[i]), ay = o * (p.cx[i] - p.bx[i]);
        gx -= 2.0 * d * ax, gy -= 2.0 * d * ay;
        hxx += 2.0 * ax * ax, hxy += 2.0 * ax * ay, hyy += 2.0 * ay * ay;
      }
      const double tr = hxx + hyy;
      if (!(tr > 0.0)) continue;
      const double det = hxx * hyy - hxy * hxy;
      double dx, dy;
      if (det > 1e-12 * tr * tr) {
        dx = -(hyy * gx - hxy * gy) / det, dy = -(hxx * gy - hxy * gx) / det;
      } else {
        dx = -gx / tr, dy = -gy / tr;
      }
      const double f = F(p, px, py);
      for (int h = 0; h <= 10; ++h, dx *= 0.5, dy *= 0.5) {
        if (!(F(p, px + dx, py + dy) < f)) continue;
        const int before = Inverted(v, p, px, py), after = Inverted(v, p, px + dx, py + dy);
        m.xy[2 * int64_t{v}] = px + dx, m.xy[2 * int64_t{v} + 1] = py + dy;
        inverted -= before - after;
        break;
      }
    }
    return 1.0 - static_cast<double>(inverted) / m.NumTriangles();
  }
};

// edge-swap: Lawson flips of edges whose opposite corner lies in the circumcircle, triangles in
// storage order, each edge from its lower-numbered triangle (core/kernels/edge_swap.cc).
struct HandEdgeSwap : Hand {
  Mesh m;
  AlignedVector<int32_t> nbr;  // as the kernel's, 64-byte aligned
  double interior_edges = 1.0;
  static bool InCircle(const double* a, const double* b, const double* c, const double* d) {
    const double ax = a[0] - d[0], ay = a[1] - d[1], bx = b[0] - d[0], by = b[1] - d[1];
    const double cx = c[0] - d[0], cy = c[1] - d[1];
    const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double det =
        ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx);
    const double mag = std::fabs(ax) * (std::fabs(by * c2) + std::fabs(b2 * cy)) +
                       std::fabs(ay) * (std::fabs(bx * c2) + std::fabs(b2 * cx)) +
                       a2 * (std::fabs(bx * cy) + std::fabs(by * cx));
    const double orient = Area2(a[0], a[1], b[0], b[1], c[0], c[1]) >= 0.0 ? 1.0 : -1.0;
    return orient * det > 1e-12 * mag;
  }
  void Repoint(int32_t x, int32_t from, int32_t to) {
    if (x < 0) return;
    for (int k = 0; k < 3; ++k)
      if (nbr[3 * int64_t{x} + k] == from) {
        nbr[3 * int64_t{x} + k] = to;
        return;
      }
  }
  void Start(const Mesh& base) override {
    m = base.Clone();
    JitterMesh(m, kJitterAmount, kJitterSeed);
    nbr.assign(m.tri.size(), -1);
    int64_t edges = 0;
    for (int32_t t = 0; t < m.NumTriangles(); ++t)
      for (int j = 0; j < 3; ++j) {
        const int32_t q = m.tri[3 * int64_t{t} + (j + 1) % 3],
                      r = m.tri[3 * int64_t{t} + (j + 2) % 3];
        for (const int32_t* u = m.v2t.RowBegin(q); u != m.v2t.RowEnd(q); ++u) {
          const int32_t* c = &m.tri[3 * int64_t{*u}];
          if (*u != t && (c[0] == r || c[1] == r || c[2] == r)) nbr[3 * int64_t{t} + j] = *u;
        }
        edges += nbr[3 * int64_t{t} + j] >= 0;
      }
    interior_edges = edges > 0 ? static_cast<double>(edges / 2) : 1.0;
  }
  double Sweep() override {
    double flips = 0.0;
    int32_t* tri = m.tri.data();
    volatile const int32_t n = m.NumTriangles();  // the bound read at each test, as the kernel's
    for (int32_t t = 0; t < n; ++t) {
      int32_t v[3] = {tri[3 * int64_t{t}], tri[3 * int64_t{t} + 1], tri[3 * int64_t{t} + 2]};
      double p[3][2];
      for (int j = 0; j < 3; ++j)
        p[j][0] = m.xy[2 * int64_t{v[j]}], p[j][1] = m.xy[2 * int64_t{v[j]} + 1];
#pragma GCC unroll 3
      for (int j = 0; j < 3; ++j) {
        const int32_t u = nbr[3 * int64_t{t} + j];
        if (u <= t) continue;
        const int jq = (j + 1) % 3, jr = (j + 2) % 3;
        const int32_t* w = tri + 3 * int64_t{u};
        const int32_t s = w[0] ^ w[1] ^ w[2] ^ v[jq] ^ v[jr];  // u's corners are Q, R and S
        const double sp[2] = {m.xy[2 * int64_t{s}], m.xy[2 * int64_t{s} + 1]};
        if (!InCircle(p[j], p[jq], p[jr], sp)) continue;
        const int ur = w[0] == v[jr] ? 0 : w[1] == v[jr] ? 1 : 2;
        const int uq = w[0] == v[jq] ? 0 : w[1] == v[jq] ? 1 : 2;
        const int32_t across_qs = nbr[3 * int64_t{u} + ur], across_sr = nbr[3 * int64_t{u} + uq];
        const int32_t across_rp = nbr[3 * int64_t{t} + jq], across_pq = nbr[3 * int64_t{t} + jr];
        const int32_t pv = v[j], qv = v[jq], rv = v[jr];
        const int32_t nt[3] = {pv, qv, s}, nu[3] = {pv, s, rv};
        const int32_t bt[3] = {across_qs, u, across_pq}, bu[3] = {across_sr, across_rp, t};
        for (int k = 0; k < 3; ++k) {
          tri[3 * int64_t{t} + k] = nt[k], tri[3 * int64_t{u} + k] = nu[k];
          nbr[3 * int64_t{t} + k] = bt[k], nbr[3 * int64_t{u} + k] = bu[k];
        }
        Repoint(across_qs, u, t);
        Repoint(across_rp, t, u);
        flips += 1.0;
        const double pp[2] = {p[j][0], p[j][1]}, pq[2] = {p[jq][0], p[jq][1]};
        v[0] = pv, v[1] = qv, v[2] = s;
        p[0][0] = pp[0], p[0][1] = pp[1], p[1][0] = pq[0], p[1][1] = pq[1];
        p[2][0] = sp[0], p[2][1] = sp[1];
      }
    }
    return 1.0 - flips / interior_edges;
  }
};

std::unique_ptr<Hand> MakeHand(const std::string& k) {
  if (k == "spmv") return std::make_unique<HandSpmv>();
  if (k == "assembly") return std::make_unique<HandAssembly>();
  if (k == "smart-laplacian") return std::make_unique<HandSmart>();
  if (k == "local-opt") return std::make_unique<HandLocalOpt>();
  if (k == "untangle") return std::make_unique<HandUntangle>();
  return std::make_unique<HandEdgeSwap>();
}

void KernelVsHand(benchmark::State& state, const std::string& name) {
  const Mesh& base = BaseMesh();
  const KernelInfo& k = ParseKernel(name);
  constexpr int kSweeps = 5;
  std::vector<double> reg_ms, hand_ms, ratio;
  for (auto _ : state) {
    Mesh m = base.Clone();
    const SmoothResult r = RunKernel(k, m, ExactSweeps(kSweeps));
    // The kernel may stop early (untangle with nothing turned over, edge-swap with nothing to
    // flip): the hand-written loop runs as many sweeps.
    const int sweeps = static_cast<int>(r.sweeps.size());
    if (sweeps < 2) return state.SkipWithError("the kernel ran fewer than two sweeps");
    std::unique_ptr<Hand> hand = MakeHand(name);
    hand->Start(base);
    std::vector<double> h, g;
    for (int s = 0; s < sweeps; ++s) {
      const auto t0 = std::chrono::steady_clock::now();
      const double measure = hand->Sweep();
      const double ms =
          1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (std::abs(measure - r.sweeps[s].quality) > 1e-9 * std::abs(r.sweeps[s].quality))
        return state.SkipWithError("the hand-written sweep's measure differs from the kernel's");
      if (s > 0) h.push_back(ms), g.push_back(1e3 * r.sweeps[s].seconds);
    }
    reg_ms.push_back(Median(g));
    hand_ms.push_back(Median(h));
    ratio.push_back(reg_ms.back() / hand_ms.back());
  }
  state.counters["kernel_ms_per_sweep"] = Median(reg_ms);
  state.counters["hand_ms_per_sweep"] = Median(hand_ms);
  PutRatios(state, "kernel/hand", ratio);
}

}  // namespace

void RegisterKernelBenchmarks() {
  for (const char* k :
       {"spmv", "assembly", "smart-laplacian", "local-opt", "untangle", "edge-swap"})
    benchmark::RegisterBenchmark((std::string("Kernel/") + k).c_str(),
                                 [k](benchmark::State& s) { KernelVsHand(s, k); })
        ->Iterations(9)
        ->Unit(benchmark::kMillisecond);
}

}  // namespace meshreuse
