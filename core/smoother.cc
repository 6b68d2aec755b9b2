// Non-template parts of the smoother: names of the update modes.
#include "core/smoother.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.h"

namespace meshreuse {

const char* UpdateModeName(UpdateMode m) {
  return m == UpdateMode::kJacobi ? "jacobi" : "gauss-seidel";
}

const char* QualityModeName(QualityMode m) {
  return m == QualityMode::kPerMove ? "per-move" : "per-sweep";
}

QualityMode ParseQualityMode(const std::string& s) {
  if (s == "per-move") return QualityMode::kPerMove;
  if (s == "per-sweep") return QualityMode::kPerSweep;
  throw UsageError("unknown quality mode '" + s + "' (per-move or per-sweep)");
}

UpdateMode ParseUpdateMode(const std::string& s) {
  if (s == "gs" || s == "gauss-seidel") return UpdateMode::kGaussSeidel;
  if (s == "jacobi") return UpdateMode::kJacobi;
  throw UsageError("unknown update mode '" + s + "' (expected gauss-seidel or jacobi)");
}

std::vector<uint64_t> AccessesPerSweep(const Mesh& m, int threads, UpdateMode mode) {
  std::vector<uint64_t> n(threads < 1 ? 1 : threads, 0);
  const int p = static_cast<int>(n.size());
  const bool gs = mode == UpdateMode::kGaussSeidel;
  const int64_t ni = static_cast<int64_t>(m.interior.size());
  for (int64_t k = 0; k < ni; ++k) {
    const int32_t v = m.interior[k];
    n[StaticOwner(k, ni, p)] += 2 + m.v2v.RowSize(v) + (gs ? 3 * m.v2t.RowSize(v) : 0);
  }
  if (!gs) {
    const int64_t nt = m.NumTriangles();
    for (int64_t t = 0; t < nt; ++t) n[StaticOwner(t, nt, p)] += 3;
  }
  return n;
}

double ThreadCpuSeconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void FlushCaches(uint64_t bytes) {
  std::vector<uint64_t> buf(bytes / 8 + 8);
  for (size_t i = 0; i < buf.size(); i += 8) buf[i] = i;
  uint64_t sum = 0;
  for (size_t i = 0; i < buf.size(); i += 8) sum += buf[i];
  volatile uint64_t keep = sum;  // the reads must happen
  (void)keep;
}

std::vector<uint64_t> RefsPerSweep(const Mesh& m, int threads, UpdateMode mode) {
  std::vector<uint64_t> n(threads < 1 ? 1 : threads, 0);
  const int p = static_cast<int>(n.size());
  const int64_t ni = static_cast<int64_t>(m.interior.size());
  for (int64_t k = 0; k < ni; ++k) {
    const int32_t v = m.interior[k];
    n[StaticOwner(k, ni, p)] += mode == UpdateMode::kGaussSeidel
                                    ? 7 + 2 * m.v2v.RowSize(v) + 13 * m.v2t.RowSize(v)
                                    : 5 + 2 * m.v2v.RowSize(v);
  }
  for (uint64_t& c : n) c += 1;  // the loop bound's last test
  if (mode == UpdateMode::kJacobi) {
    const int64_t nt = m.NumTriangles();
    for (int64_t t = 0; t < nt; ++t) n[StaticOwner(t, nt, p)] += 12;
    for (uint64_t& c : n) c += 1;
  }
  return n;
}

namespace smoother_detail {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
double
WeightedQualitySum(const double* xy, const int32_t* tri, const double* wq, int64_t b, int64_t e) {
  double s = 0.0;
#pragma omp simd reduction(+ : s)
  for (int64_t t = b; t < e; ++t) s += wq[2 * t] * TriangleQualityAt(xy, tri, t);
  return s;
}

}  // namespace smoother_detail

}  // namespace meshreuse
