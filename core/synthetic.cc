// MakeSyntheticMesh; see synthetic.h.
#include "core/synthetic.h"

#include <algorithm>
#include <vector>

namespace meshreuse {

RawMesh MakeSyntheticMesh(const SyntheticOptions& opt) {
  SplitMix64 rng(opt.seed);
  const int nx = std::max(1, opt.nx), ny = std::max(1, opt.ny);
  const double jitter = std::clamp(opt.jitter, 0.0, 0.24);
  std::vector<double> w(nx), h(ny), X(nx + 1, 0.0), Y(ny + 1, 0.0);
  for (double& v : w) v = opt.graded ? 0.15 + 0.85 * rng.Uniform() : 1.0;
  for (double& v : h) v = opt.graded ? 0.15 + 0.85 * rng.Uniform() : 1.0;
  for (int i = 0; i < nx; ++i) X[i + 1] = X[i] + w[i];
  for (int j = 0; j < ny; ++j) Y[j + 1] = Y[j] + h[j];

  // Holes: cells whose centre lies in a circle are removed.
  struct Circle {
    double x, y, r;
  };
  std::vector<Circle> holes;
  for (int k = 0; k < opt.holes; ++k)
    holes.push_back({X[nx] * (0.2 + 0.6 * rng.Uniform()), Y[ny] * (0.2 + 0.6 * rng.Uniform()),
                     std::min(X[nx], Y[ny]) * (0.08 + 0.12 * rng.Uniform())});
  auto in_hole = [&](double x, double y) {
    for (const Circle& c : holes)
      if ((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y) < c.r * c.r) return true;
    return false;
  };

  const auto pid = [&](int i, int j) { return j * (nx + 1) + i; };
  std::vector<int32_t> tri;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const bool diag = rng.Below(2) == 0;
      if (in_hole(0.5 * (X[i] + X[i + 1]), 0.5 * (Y[j] + Y[j + 1]))) continue;
      const int32_t a = pid(i, j), b = pid(i + 1, j), c = pid(i + 1, j + 1), d = pid(i, j + 1);
      if (diag)
        tri.insert(tri.end(), {a, b, c, a, c, d});
      else
        tri.insert(tri.end(), {a, b, d, b, c, d});
    }

  // Jittered points; only the ones a triangle uses are kept, in grid order.
  const int np = (nx + 1) * (ny + 1);
  std::vector<int32_t> id(np, -1);
  for (int32_t v : tri) id[v] = 0;
  RawMesh raw;
  raw.vertex_file = raw.triangle_file = "<synthetic>";
  int32_t next = 0;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double lx = std::min(i > 0 ? w[i - 1] : w[i], i < nx ? w[i] : w[i - 1]);
      const double ly = std::min(j > 0 ? h[j - 1] : h[j], j < ny ? h[j] : h[j - 1]);
      const double dx = (2.0 * rng.Uniform() - 1.0) * jitter * lx;
      const double dy = (2.0 * rng.Uniform() - 1.0) * jitter * ly;
      if (id[pid(i, j)] < 0) continue;
      id[pid(i, j)] = next++;
      raw.xy.push_back(X[i] + dx);
      raw.xy.push_back(Y[j] + dy);
    }
  for (int32_t& v : tri) v = id[v];
  raw.tri.assign(tri.begin(), tri.end());
  return raw;
}

}  // namespace meshreuse
