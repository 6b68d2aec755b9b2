// The working set of one sweep per kernel; see working_set.h.
#include "reports/working_set.h"

#include <array>

#include "analysis/line_marks.h"
#include "core/access.h"
#include "core/kernels/kernel.h"
#include "tracer/access_stream.h"

namespace meshreuse {

namespace {

// Per line, the last sweep that touched it and the arrays (tags) that touched it in that sweep:
// two tags on one array (the weights and the qualities) count the line once in the total and once
// for each tag.
class LineCount : public AccessConsumer {
 public:
  explicit LineCount(uint32_t line_bytes) : line_bytes_(line_bytes) {}
  void Begin(const StreamInfo& info) override {
    marks_ = LineMarks<Mark>(info.canonical, line_bytes_);
  }
  void BeginSweep(int sweep) override {
    if (sweep <= 1) return;  // the first sweep keeps what came before it
    sweep_ = static_cast<uint32_t>(sweep);
    accesses_ = lines_ = 0;
    per_array_.fill(0);
  }
  void Consume(const Access* a, size_t n) override {
    static_assert(kArrays < 32, "a tag's bit in Mark::tags");
    accesses_ += n;
    for (size_t k = 0; k < n; ++k) {
      Mark* mark = &marks_.At(a[k].address / line_bytes_);
      if (mark->sweep != sweep_) {
        *mark = Mark{sweep_, 0};
        ++lines_;
      }
      const uint32_t tag = a[k].array < kArrays ? a[k].array : kArrays;
      if (!(mark->tags >> tag & 1)) {
        mark->tags |= uint32_t{1} << tag;
        ++per_array_[tag];
      }
    }
  }
  uint64_t accesses() const { return accesses_; }
  uint64_t lines() const { return lines_; }
  // Index kArrays: accesses outside the smoother's arrays (none from a kernel).
  const std::array<uint64_t, kArrays + 1>& per_array() const { return per_array_; }

 private:
  struct Mark {
    uint32_t sweep = 0, tags = 0;
  };
  uint32_t line_bytes_;
  uint32_t sweep_ = 1;
  uint64_t accesses_ = 0, lines_ = 0;
  std::array<uint64_t, kArrays + 1> per_array_{};
  LineMarks<Mark> marks_;
};

}  // namespace

std::vector<KernelWorkingSet> KernelWorkingSets(const Mesh& mesh,
                                                const std::vector<std::string>& kernels,
                                                uint32_t line_bytes, const Log& log) {
  std::vector<KernelWorkingSet> out;
  for (const std::string& name : kernels) {
    const KernelInfo& k = ParseKernel(name);
    log.Say("working set: two traced sweeps of " + name);
    Mesh work = mesh.Clone();
    LineCount count(line_bytes);
    StreamMesh(work, ExactSweeps(2), "mesh", "as stored", count, &k);
    KernelWorkingSet w;
    w.kernel = name;
    w.accesses = count.accesses();
    w.lines = count.lines();
    for (int i = 0; i <= kArrays; ++i) {
      const uint64_t l = count.per_array()[static_cast<size_t>(i)];
      if (l == 0) continue;
      w.arrays.emplace_back(i < kArrays ? ArrayName(static_cast<Array>(i)) : "other", l);
    }
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace meshreuse
