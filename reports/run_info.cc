// run.json helpers; see run_info.h.
#include "reports/run_info.h"

#include <sys/resource.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

#include "build_info.h"  // generated at build time: MESHREUSE_GIT_REV, MESHREUSE_GIT_DIRTY
#include "core/orderings/registry.h"

namespace meshreuse {

namespace {
Json CacheSizesJson() {
  // Linux's description of cpu0's caches: {"L1d": "48K", "L2": "1280K", ...}.
  Json s = Json::object();
  for (int i = 0; i < 16; ++i) {
    const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(i) + "/";
    std::ifstream level(dir + "level"), type(dir + "type"), size(dir + "size");
    std::string l, t, z;
    if (!(level >> l) || !(type >> t) || !(size >> z)) break;
    if (t == "Instruction") continue;
    const std::string name = "L" + l + (t == "Data" ? "d" : "");
    s[name] = z;
  }
  return s;
}
}  // namespace

Json MachineJson() {
  char host[256] = "unknown";
  ::gethostname(host, sizeof host - 1);
  std::string cpu = "unknown";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const size_t c = line.find(':');
      if (c != std::string::npos) cpu = line.substr(c + 2);
      break;
    }
  struct utsname u {};
  std::string os = "unknown";
  if (::uname(&u) == 0) os = std::string(u.sysname) + " " + u.release + " " + u.machine;
  Json j;
  j["hostname"] = host;
  j["cpu"] = cpu;
  j["cores"] = std::thread::hardware_concurrency();
  j["os"] = os;
  j["caches"] = CacheSizesJson();
  j["compiler"] = __VERSION__;
  return j;
}

std::string GitRevision() {
  return std::string(MESHREUSE_GIT_REV) + (MESHREUSE_GIT_DIRTY ? "-dirty" : "");
}

std::string VersionString() {
  return std::string("meshreuse ") + MESHREUSE_VERSION + " (git " + GitRevision() + ", " +
         MESHREUSE_BUILD_TYPE + ", " + MESHREUSE_COMPILER + ")";
}

Json BuildJson() {
  Json j;
  j["version"] = MESHREUSE_VERSION;
  j["git_revision"] = MESHREUSE_GIT_REV;
  j["git_dirty"] = static_cast<bool>(MESHREUSE_GIT_DIRTY);
  j["compiler"] = MESHREUSE_COMPILER;
  j["compiler_version"] = __VERSION__;
  j["build_type"] = MESHREUSE_BUILD_TYPE;
  j["flags"] = MESHREUSE_CXX_FLAGS;
  return j;
}

uint64_t PeakRssBytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<uint64_t>(u.ru_maxrss) * 1024;  // Linux: kilobytes
}

std::string UtcTimestamp() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

Json RunJson(const std::string& tool, const std::vector<std::string>& command_line,
             const Json& configuration, const Json& extra) {
  Json j;
  j["tool"] = tool;
  j["command"] = command_line;
  j["git_revision"] = GitRevision();
  j["build"] = BuildJson();
  j["time_utc"] = UtcTimestamp();
  j["machine"] = MachineJson();
  j["configuration"] = configuration;
  for (const auto& [k, v] : extra.items()) j[k] = v;
  return j;
}

std::string RunJsonText(const Json& run) { return run.dump(2) + "\n"; }

Json OrderingSeedsJson(const std::vector<OrderingSpec>& specs, uint64_t seed) {
  Json seeds = Json::object();
  for (const auto& [label, s] : SeededOrderings(specs, seed)) seeds[label] = s;
  return seeds;
}

std::vector<std::string> OrderingTexts(const std::vector<OrderingSpec>& specs) {
  std::vector<std::string> t;
  for (const OrderingSpec& s : specs) t.push_back(s.text);
  return t;
}

}  // namespace meshreuse
