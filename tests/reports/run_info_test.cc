// run.json: one writer for every command, with the machine, the build and the configuration.
#include "reports/run_info.h"

#include <gtest/gtest.h>

namespace meshreuse {
namespace {

TEST(RunJson, MachineBuildAndConfiguration) {
  EXPECT_TRUE(MachineJson().contains("caches"));
  EXPECT_FALSE(GitRevision().empty());
  const Json b = BuildJson();  // the build's revision, type and flags for run.json
  for (const char* key : {"git_revision", "git_dirty", "build_type", "flags"})
    EXPECT_TRUE(b.contains(key)) << key;
  const Json r = RunJson("meshreuse test", {"meshreuse", "x"}, Json{{"seed", 7}},
                         Json{{"counters", "simulated"}});
  const Json back = Json::parse(RunJsonText(r));
  std::vector<std::string> keys;
  for (const auto& [k, v] : back.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"tool", "command", "git_revision", "build", "time_utc",
                                            "machine", "configuration", "counters"}));
  EXPECT_EQ(back["configuration"]["seed"], 7);
}

}  // namespace
}  // namespace meshreuse
