// Non-template parts of the smoother: names of the update modes.
#include "core/smoother.h"

#include <stdexcept>

namespace meshreuse {

const char* UpdateModeName(UpdateMode m) {
  return m == UpdateMode::kJacobi ? "jacobi" : "gauss-seidel";
}

UpdateMode ParseUpdateMode(const std::string& s) {
  if (s == "gs" || s == "gauss-seidel") return UpdateMode::kGaussSeidel;
  if (s == "jacobi") return UpdateMode::kJacobi;
  throw std::invalid_argument("unknown update mode '" + s + "' (expected gauss-seidel or jacobi)");
}

std::vector<uint64_t> AccessesPerSweep(const Mesh& m, int threads) {
  std::vector<uint64_t> n(threads < 1 ? 1 : threads, 0);
  const int64_t ni = static_cast<int64_t>(m.interior.size());
  for (int64_t k = 0; k < ni; ++k) {
    const int32_t v = m.interior[k];
    n[smoother_detail::StaticOwner(k, ni, static_cast<int>(n.size()))] +=
        2 + m.v2v.RowSize(v) + 3 * m.v2t.RowSize(v);
  }
  return n;
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
    n[smoother_detail::StaticOwner(k, ni, p)] +=
        mode == UpdateMode::kGaussSeidel ? 7 + 2 * m.v2v.RowSize(v) + 13 * m.v2t.RowSize(v)
                                         : 5 + 2 * m.v2v.RowSize(v);
  }
  for (uint64_t& c : n) c += 1;  // the loop bound's last test
  if (mode == UpdateMode::kJacobi) {
    const int64_t nt = m.NumTriangles();
    for (int64_t t = 0; t < nt; ++t) n[smoother_detail::StaticOwner(t, nt, p)] += 12;
    for (uint64_t& c : n) c += 1;
  }
  return n;
}

}  // namespace meshreuse
