// The working set of one sweep per kernel (reports/working_set.h, `mesh info --kernels`): the
// spmv's against its closed form (it reads every byte of its five arrays once a sweep), and every
// kernel's against a naive count of the last traced sweep's distinct lines (a std::set per
// array over the recorded stream).
#include "reports/working_set.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/access.h"
#include "core/error.h"
#include "core/kernels/kernel.h"
#include "tests/test_util.h"
#include "tracer/access_stream.h"

namespace meshreuse {
namespace {

constexpr uint64_t kLine = 64;

uint64_t Lines(uint64_t bytes) { return (bytes + kLine - 1) / kLine; }

TEST(WorkingSet, SpmvReadsEveryByteOfItsArraysOnceASweep) {
  for (const char* file : {"plate41.msh", "two_interior.node"}) {
    const Mesh m = ReadMesh(testing::DataPath(file));
    const std::vector<KernelWorkingSet> w = KernelWorkingSets(m, {"spmv"}, kLine, Log());
    ASSERT_EQ(w.size(), 1u);
    const uint64_t v = static_cast<uint64_t>(m.NumVertices());
    const uint64_t nnz = v + m.v2v.idx.size();  // a row per vertex: its neighbours and itself
    // off (V + 1) x 8 B, col nnz x 4 B, val nnz x 8 B, x and y V x 8 B each, the loop bound's slot.
    const std::map<std::string, uint64_t> want = {
        {"A.off", Lines(8 * (v + 1))}, {"A.col", Lines(4 * nnz)}, {"A.val", Lines(8 * nnz)},
        {"x", Lines(8 * v)},           {"y", Lines(8 * v)},       {"bound", 1}};
    std::map<std::string, uint64_t> got(w[0].arrays.begin(), w[0].arrays.end());
    EXPECT_EQ(got, want) << file;
    uint64_t total = 0;
    for (const auto& [name, lines] : want) total += lines;
    EXPECT_EQ(w[0].lines, total) << file;
    // Per row 5 + 3 nnz(i) accesses (spmv.cc's documented sequence), and the bound once more.
    EXPECT_EQ(w[0].accesses, 5 * v + 3 * nnz + 1) << file;
  }
}

// Every access of the last sweep, kept.
struct LastSweep : AccessConsumer {
  std::vector<Access> kept;
  void Begin(const StreamInfo&) override {}
  void BeginSweep(int s) override {
    if (s > 1) kept.clear();
  }
  void Consume(const Access* a, size_t n) override { kept.insert(kept.end(), a, a + n); }
};

TEST(WorkingSet, EveryKernelEqualsANaiveCountOfItsLastSweep) {
  const Mesh meshes[] = {ReadMesh(testing::DataPath("plate41.msh")),
                         testing::Synthetic(20, 14, 2, 7)};
  std::vector<std::string> names;
  for (const KernelInfo& k : Kernels()) names.push_back(k.name);
  for (const Mesh& m : meshes) {
    const std::vector<KernelWorkingSet> w = KernelWorkingSets(m, names, kLine, Log());
    ASSERT_EQ(w.size(), names.size());
    for (size_t i = 0; i < names.size(); ++i) {
      Mesh work = m.Clone();
      LastSweep rec;
      StreamMesh(work, ExactSweeps(2), "m", "as stored", rec, &ParseKernel(names[i]));
      std::map<std::string, std::set<uint64_t>> lines;
      std::set<uint64_t> all;
      for (const Access& a : rec.kept) {
        lines[ArrayName(static_cast<Array>(a.array))].insert(a.address / kLine);
        all.insert(a.address / kLine);
      }
      std::map<std::string, uint64_t> want, got(w[i].arrays.begin(), w[i].arrays.end());
      for (const auto& [name, set] : lines) want[name] = set.size();
      EXPECT_EQ(w[i].kernel, names[i]);
      EXPECT_EQ(got, want) << names[i];
      EXPECT_EQ(w[i].lines, all.size()) << names[i];
      EXPECT_EQ(w[i].accesses, rec.kept.size()) << names[i];
      EXPECT_GT(w[i].lines, 0u) << names[i];
    }
  }
}

TEST(WorkingSet, AnUnknownKernelIsAUsageError) {
  const Mesh m = testing::TwoInterior();
  EXPECT_THROW(KernelWorkingSets(m, {"laplacian", "no-such"}, kLine, Log()), UsageError);
}

}  // namespace
}  // namespace meshreuse
