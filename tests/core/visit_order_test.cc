// ReadVisitOrder (core/visit_order.h): a valid order replaces the interior list and the smoother
// follows it; every malformed file is refused naming its line.
#include "core/visit_order.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "core/smoother.h"
#include "tests/test_util.h"

namespace meshreuse {
namespace {
using namespace testing;

std::string Write(const std::string& text) {
  const std::string path = ::testing::TempDir() + "/visit_order_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                           std::to_string(std::hash<std::string>()(text)) + ".txt";
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const std::string& text, const Mesh& m) {
  try {
    ReadVisitOrder(Write(text), m);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(VisitOrder, ReversedOrderIsReadAndFollowed) {
  const Mesh m = TwoInterior();  // interior vertices 6 and 7
  const AlignedVector<int32_t> order = ReadVisitOrder(Write("# comment\n7\n6\n"), m);
  ASSERT_EQ(order.size(), 2u);
  EXPECT_EQ(order[0], 7);
  EXPECT_EQ(order[1], 6);
  Mesh a = m.Clone(), b = m.Clone();
  b.interior = order;
  Smooth(a, ExactSweeps(1));
  Smooth(b, ExactSweeps(1));
  EXPECT_NE(a.xy, b.xy);  // 6 and 7 are neighbours: the order shows in the result
}

TEST(VisitOrder, RefusesEachProblemByLine) {
  const Mesh m = TwoInterior();
  EXPECT_NE(ErrorOf("6\nx\n", m).find(":2:"), std::string::npos);
  EXPECT_NE(ErrorOf("6\n8\n", m).find("outside 0..7"), std::string::npos);
  EXPECT_NE(ErrorOf("6\n0\n", m).find("vertex 0 is on the boundary"), std::string::npos);
  EXPECT_NE(ErrorOf("6\n6\n", m).find("repeated (first on line 1)"), std::string::npos);
  EXPECT_NE(ErrorOf("6\n", m).find("vertex 7 is missing"), std::string::npos);
  EXPECT_NE(ErrorOf("6 7\n", m).find("one vertex id per line"), std::string::npos);
}

}  // namespace
}  // namespace meshreuse
