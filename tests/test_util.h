// Shared helpers for the test suites: paths to tests/data and small meshes.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "core/mesh.h"
#include "core/mesh_io.h"
#include "core/synthetic.h"
#include "tracer/access_stream.h"

namespace meshreuse::testing {

// A fresh folder under the system temp dir, removed with everything in it at scope exit.
class TempDir {
 public:
  TempDir() {
    std::string t = (std::filesystem::temp_directory_path() / "meshreuse-test-XXXXXX").string();
    if (!::mkdtemp(t.data())) throw std::runtime_error("mkdtemp failed");
    path_ = t;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A file's bytes, and bytes written as a file (the tests that damage binary files).
inline std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
inline void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
inline bool HasText(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

inline std::string DataPath(const std::string& name) {
  return std::string(MESHREUSE_TEST_DATA) + "/" + name;
}

// A synthetic mesh (core/synthetic.h) of nx x ny cells with `holes` holes: the tests' one builder.
inline Mesh Synthetic(int nx, int ny, int holes, uint64_t seed) {
  SyntheticOptions o;
  o.nx = nx, o.ny = ny, o.holes = holes, o.seed = seed;
  return BuildMesh(MakeSyntheticMesh(o));
}

// The meshes the ordering and permutation tests loop over: 24 synthetic meshes (holes, graded
// cells, sizes 4..26 x 3..19, boundary vertices with no interior neighbour) plus two_interior and
// two_components (a component without interior vertices).
inline std::vector<Mesh> MeshCorpus() {
  std::vector<Mesh> meshes;
  for (uint64_t seed = 1; seed <= 24; ++seed) {
    SyntheticOptions o;
    o.nx = 4 + static_cast<int>(seed * 7 % 23);
    o.ny = 3 + static_cast<int>(seed * 5 % 17);
    o.holes = static_cast<int>(seed % 4);
    o.graded = seed % 3 != 0;
    o.seed = seed;
    RawMesh raw = MakeSyntheticMesh(o);
    if (!raw.tri.empty()) meshes.push_back(BuildMesh(std::move(raw)));
  }
  meshes.push_back(ReadMesh(DataPath("two_interior.node")));
  meshes.push_back(ReadMesh(DataPath("two_components.node")));
  return meshes;
}

// The unit square as two triangles, vertices (0,0), (1,0), (0,1), (1,1): the curve orderings'
// hand-checked case.
inline Mesh UnitSquare() {
  RawMesh raw;
  raw.xy = {0, 0, 1, 0, 0, 1, 1, 1};
  raw.tri = {0, 1, 3, 0, 3, 2};
  return BuildMesh(std::move(raw));
}

// The hand-computed sweep's mesh: boundary vertices 0..5 on a 4 x 2 rectangle, interior 6 and 7.
inline Mesh TwoInterior() { return ReadMesh(DataPath("two_interior.node")); }

// Keeps every access a stream delivers, with the sweep each begins (tracer/access_stream.h).
struct RecordingConsumer : AccessConsumer {
  StreamInfo info;
  std::vector<Access> all;
  std::vector<size_t> sweep_starts;
  void Begin(const StreamInfo& i) override { info = i; }
  void BeginSweep(int) override { sweep_starts.push_back(all.size()); }
  void Consume(const Access* a, size_t n) override { all.insert(all.end(), a, a + n); }
};

}  // namespace meshreuse::testing
