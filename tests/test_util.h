// Shared helpers for the test suites: paths to tests/data and small meshes.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/mesh.h"
#include "core/mesh_io.h"

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

inline std::string DataPath(const std::string& name) {
  return std::string(MESHREUSE_TEST_DATA) + "/" + name;
}

// The hand-computed sweep's mesh: boundary vertices 0..5 on a 4 x 2 rectangle, interior 6 and 7.
inline Mesh TwoInterior() { return ReadMesh(DataPath("two_interior.node")); }

}  // namespace meshreuse::testing
