// Meshing the shipped shapes with Triangle: every shape reaches small and medium targets within 5%
// and the result reads back as a valid mesh. Skipped (with the reason) when `triangle` is absent;
// scripts/test.sh installs it, so CI runs these.
#include "core/triangle_runner.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/mesh_io.h"
#include "core/shapes.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {

namespace fs = std::filesystem;

class TriangleRunner : public ::testing::Test {
 protected:
  void SetUp() override {
    if (FindProgram("triangle").empty())
      GTEST_SKIP() << "the 'triangle' program is not installed (Debian triangle-bin, non-free)";
  }
  testing::TempDir tmp_;
  const fs::path& dir_ = tmp_.path();
};

TEST_F(TriangleRunner, EveryShapeHitsSmallAndMediumTargets) {
  for (const ShapeInfo& s : Shapes())
    for (int64_t target : {1000, 20000}) {
      SCOPED_TRACE(std::string(s.name) + " " + std::to_string(target));
      TriangulateOptions o;
      o.target_vertices = target;
      o.accept = 0.05;
      const std::string prefix = (dir_ / (std::string(s.name) + std::to_string(target))).string();
      const TriangulateResult r = TriangulatePoly(ShapesDir() + "/" + s.name + ".poly", prefix, o);
      EXPECT_NEAR(static_cast<double>(r.vertices), static_cast<double>(target), 0.05 * target);
      std::vector<std::string> warnings;
      const Mesh m = ReadMesh(prefix, &warnings);
      EXPECT_EQ(m.NumVertices(), r.vertices);
      EXPECT_EQ(m.NumTriangles(), r.triangles);
      EXPECT_TRUE(warnings.empty()) << warnings[0];
      EXPECT_GT(static_cast<int64_t>(m.interior.size()),
                m.NumBoundary());  // a mesh, not an outline
    }
  // Nothing but the results is left behind: no scratch folders.
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().rfind(".meshreuse-triangle", 0), std::string::npos);
}

TEST_F(TriangleRunner, HolesAreHoles) {
  // The valve has a bore and six bolt holes: seven inner boundary loops plus the outer one. With
  // boundary vertices found topologically, its boundary edges form 8 loops; we check the cheaper
  // consequence that no vertex lies inside the bore (radius 150 around (500, 500)).
  TriangulateOptions o;
  o.target_vertices = 5000;
  const std::string prefix = (dir_ / "valve").string();
  TriangulatePoly(ShapesDir() + "/valve.poly", prefix, o);
  const Mesh m = ReadMesh(prefix);
  for (int32_t v = 0; v < m.NumVertices(); ++v) {
    const double dx = m.xy[2 * v] - 500, dy = m.xy[2 * v + 1] - 500;
    ASSERT_GE(dx * dx + dy * dy, 149.0 * 149.0) << "vertex " << v << " inside the bore";
  }
}

TEST(TriangleRunnerErrors, MissingProgramSaysHowToInstall) {
  TriangulateOptions o;
  o.target_vertices = 1000;
  o.program = "/nonexistent/triangle";
  try {
    TriangulatePoly(ShapesDir() + "/carabiner.poly", "/tmp/never", o);
    FAIL() << "no error";
  } catch (const EnvironmentError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle-bin"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("non-free"), std::string::npos) << e.what();
  }
}

TEST(Shapes, TableMatchesThePaperAndFilesExist) {
  ASSERT_EQ(Shapes().size(), 9u);
  EXPECT_EQ(FindShape("carabiner")->paper_vertices, 328082);
  EXPECT_EQ(FindShape("wrench")->paper_triangles, 771097);
  EXPECT_EQ(FindShape("nope"), nullptr);
  for (const ShapeInfo& s : Shapes())
    EXPECT_TRUE(fs::exists(ShapesDir() + "/" + s.name + ".poly")) << s.name;
}

}  // namespace
}  // namespace meshreuse
