// Shared by the fuzz harnesses: the fuzzer's bytes as a file the readers can open by path (an
// in-memory file, /proc/self/fd/N), and what every harness does with a mesh a reader accepted --
// build it, run one smoothing sweep, compute and apply every ordering -- so a hostile input that
// slips past a reader is caught where it would hurt.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/mesh.h"
#include "core/orderings/registry.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "core/synthetic.h"

namespace meshreuse::fuzz {

class MemFile {
 public:
  MemFile(const uint8_t* data, size_t size) {
    fd_ = ::memfd_create("meshreuse-fuzz", 0);
    if (fd_ < 0) __builtin_trap();
    for (size_t off = 0; off < size;) {
      const ssize_t n = ::write(fd_, data + off, size - off);
      if (n <= 0) __builtin_trap();
      off += static_cast<size_t>(n);
    }
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  ~MemFile() { ::close(fd_); }
  MemFile(const MemFile&) = delete;
  MemFile& operator=(const MemFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  int fd_;
  std::string path_;
};

// Everything downstream of a reader, on what it accepted. InputError (a topology problem found
// while building) is an accepted outcome; anything else escapes and is a finding.
inline void Exercise(RawMesh raw) {
  Mesh m;
  try {
    m = BuildMesh(std::move(raw));
  } catch (const InputError&) {
    return;
  }
  {
    Mesh s = m.Clone();
    SmoothOptions o;
    o.max_iters = 1;
    Smooth(s, o);
  }
  for (const OrderingInfo& o : Orderings()) {
    if (o.takes_argument()) continue;
    const Permutation p = ComputeOrdering(o.name, m, 1);
    ApplyPermutation(m, p, TriangleOrder::kSorted);
  }
}

// The 20 x 15 synthetic mesh the permutation and visit-order harnesses read their files against.
inline const Mesh& SmallMesh() {
  static const Mesh mesh = [] {
    SyntheticOptions so;
    so.nx = 20, so.ny = 15, so.seed = 1;
    return BuildMesh(MakeSyntheticMesh(so));
  }();
  return mesh;
}

}  // namespace meshreuse::fuzz
