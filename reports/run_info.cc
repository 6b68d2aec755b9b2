// run.json helpers; see run_info.h.
#include "reports/run_info.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

#include "build_info.h"  // generated at build time: MESHREUSE_GIT_REV, MESHREUSE_GIT_DIRTY

namespace meshreuse {

std::string JsonString(const std::string& s) {
  std::string o = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"':
        o += "\\\"";
        break;
      case '\\':
        o += "\\\\";
        break;
      case '\n':
        o += "\\n";
        break;
      case '\t':
        o += "\\t";
        break;
      case '\r':
        o += "\\r";
        break;
      default:
        if (c < 0x20) {
          char b[8];
          std::snprintf(b, sizeof b, "\\u%04x", c);
          o += b;
        } else {
          o += static_cast<char>(c);
        }
    }
  }
  return o + "\"";
}

std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  if (v == std::floor(v) && std::fabs(v) < 9007199254740992.0) {  // an integer: no exponent
    char b[32];
    std::snprintf(b, sizeof b, "%.0f", v);
    return b;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  double back = 0;
  for (int p = 6; p <= 17; ++p) {  // the shortest that reads back exactly
    char b[32];
    std::snprintf(b, sizeof b, "%.*g", p, v);
    if (std::sscanf(b, "%lf", &back) == 1 && back == v) return b;
  }
  return buf;
}

namespace {
std::string CacheSizesJson() {
  // Linux's description of cpu0's caches: {"L1d": "48K", "L2": "1280K", ...}.
  std::string s;
  for (int i = 0; i < 16; ++i) {
    const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(i) + "/";
    std::ifstream level(dir + "level"), type(dir + "type"), size(dir + "size");
    std::string l, t, z;
    if (!(level >> l) || !(type >> t) || !(size >> z)) break;
    if (t == "Instruction") continue;
    const std::string name = "L" + l + (t == "Data" ? "d" : "");
    s += (s.empty() ? "" : ", ") + JsonString(name) + ": " + JsonString(z);
  }
  return "{" + s + "}";
}
}  // namespace

std::string MachineJson() {
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
  return "{\"hostname\": " + JsonString(host) + ", \"cpu\": " + JsonString(cpu) +
         ", \"cores\": " + std::to_string(std::thread::hardware_concurrency()) +
         ", \"os\": " + JsonString(os) + ", \"caches\": " + CacheSizesJson() +
         ", \"compiler\": " + JsonString(__VERSION__) + "}";
}

std::string GitRevision() {
  return std::string(MESHREUSE_GIT_REV) + (MESHREUSE_GIT_DIRTY ? "-dirty" : "");
}

std::string VersionString() {
  return std::string("meshreuse ") + MESHREUSE_VERSION + " (git " + GitRevision() + ", " +
         MESHREUSE_BUILD_TYPE + ", " + MESHREUSE_COMPILER + ")";
}

std::string BuildJson() {
  return "{\"version\": " + JsonString(MESHREUSE_VERSION) +
         ", \"git_revision\": " + JsonString(MESHREUSE_GIT_REV) +
         ", \"git_dirty\": " + (MESHREUSE_GIT_DIRTY ? "true" : "false") +
         ", \"compiler\": " + JsonString(MESHREUSE_COMPILER) +
         ", \"compiler_version\": " + JsonString(__VERSION__) +
         ", \"build_type\": " + JsonString(MESHREUSE_BUILD_TYPE) +
         ", \"flags\": " + JsonString(MESHREUSE_CXX_FLAGS) + "}";
}

std::string UtcTimestamp() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string CommandLineJson(const std::vector<std::string>& argv) {
  std::string s = "[";
  for (size_t i = 0; i < argv.size(); ++i) s += (i ? ", " : "") + JsonString(argv[i]);
  return s + "]";
}

}  // namespace meshreuse
