// Table rendering and the JSON helpers of run.json.
#include "reports/table.h"

#include <gtest/gtest.h>

#include "reports/run_info.h"

namespace meshreuse {
namespace {

TEST(Table, AlignedCsvMarkdown) {
  Table t({"mesh", "sweeps", "q"});
  t.AddRow({"carabiner", "65", "0.8253"});
  t.AddRow({"a,b", "7", "1.0000"});
  EXPECT_EQ(t.Aligned(),
            "mesh       sweeps       q\n"
            "-------------------------\n"
            "carabiner      65  0.8253\n"
            "a,b             7  1.0000\n");
  EXPECT_EQ(t.Csv(), "mesh,sweeps,q\ncarabiner,65,0.8253\n\"a,b\",7,1.0000\n");
  EXPECT_EQ(
      t.Markdown(),
      "| mesh | sweeps | q |\n|---|---|---|\n| carabiner | 65 | 0.8253 |\n| a,b | 7 | 1.0000 |\n");
  EXPECT_THROW(t.AddRow({"short"}), std::logic_error);
}

TEST(Format, GroupedAndFixed) {
  EXPECT_EQ(Grouped(0), "0");
  EXPECT_EQ(Grouped(999), "999");
  EXPECT_EQ(Grouped(1000), "1,000");
  EXPECT_EQ(Grouped(328082), "328,082");
  EXPECT_EQ(Grouped(-1234567), "-1,234,567");
  EXPECT_EQ(Fixed(0.8253371, 4), "0.8253");
}

TEST(Json, StringsAndNumbers) {
  EXPECT_EQ(JsonString("a\"b\\c\n\x01"), "\"a\\\"b\\\\c\\n\\u0001\"");
  EXPECT_EQ(JsonNumber(0.1), "0.1");
  EXPECT_EQ(JsonNumber(5e-6), "5e-06");
  EXPECT_EQ(JsonNumber(1.0 / 3), "0.3333333333333333");  // shortest that reads back
  EXPECT_EQ(JsonNumber(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(MachineJson().front(), '{');
  EXPECT_FALSE(GitRevision().empty());
}

}  // namespace
}  // namespace meshreuse
