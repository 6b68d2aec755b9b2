// TriangulatePoly; see triangle_runner.h.
#include "core/triangle_runner.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/text_file.h"

namespace meshreuse {

namespace fs = std::filesystem;

std::string FindProgram(const std::string& program) {
  if (program.find('/') != std::string::npos)
    return ::access(program.c_str(), X_OK) == 0 ? program : "";
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    const std::string p = (dir.empty() ? "." : dir) + "/" + program;
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return "";
}

namespace {

// Removes the scratch folder however we leave.
struct ScratchDir {
  fs::path path;
  ~ScratchDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

// Runs argv in `dir` with stdout and stderr to `log`; returns the exit status (-1 if signalled).
int Run(const std::vector<std::string>& argv, const fs::path& dir, const fs::path& log) {
  const pid_t pid = ::fork();
  if (pid < 0) throw EnvironmentError("triangle", "fork failed");
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(126);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw EnvironmentError("triangle", "waitpid failed");
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string Tail(const fs::path& log) {
  std::ifstream in(log);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (all.size() > 600) all = "..." + all.substr(all.size() - 600);
  return all;
}

int64_t HeaderCount(const fs::path& p) {
  TextFile f(p.string());
  std::string_view line, tok;
  if (!f.NextDataLine(&line) || !Tokens(line).Next(&tok)) f.Fail("Triangle wrote an empty file");
  return f.ParseInt(tok, "the count");
}

// Checks what Triangle would stumble over, naming the .poly's line: vertices in the file (at
// least 3, finite, a box of positive area below 1e30 so that the area bound Triangle reads is a
// plain decimal), segments and holes as many as their counts say, each segment between two of
// the vertices. Returns the vertices' bounding-box area, for the first guess of the triangle area.
double CheckPolyFile(const std::string& poly) {
  TextFile f(poly);
  std::string_view line, tok[8];
  if (!f.NextDataLine(&line)) f.Fail("empty .poly file");
  if (Tokens(line).Split(tok, 8) < 1) f.Fail("bad .poly header");
  const int64_t n = f.ParseInt(tok[0], "the number of vertices");
  if (n < 3)
    f.Fail("a .poly outline needs its vertices in the file (found " + std::to_string(n) + ")");
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  int64_t base = 0;
  for (int64_t i = 0; i < n; ++i) {
    if (!f.NextDataLine(&line))
      f.Fail("file ends after " + std::to_string(i) + " of the " + std::to_string(n) +
             " vertices the header announces");
    if (Tokens(line).Split(tok, 8) < 3) f.Fail("a vertex line should read 'id x y ...'");
    if (i == 0) base = f.ParseInt(tok[0], "the vertex number");
    const double x = f.ParseDouble(tok[1], "x"), y = f.ParseDouble(tok[2], "y");
    if (!std::isfinite(x) || !std::isfinite(y)) f.Fail("a vertex coordinate is not finite");
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  const double a = (x1 - x0) * (y1 - y0);
  if (!(a > 0)) f.Fail("the .poly vertices span no area");
  if (!(a < 1e30))
    f.Fail("the .poly vertices span an area of " + std::to_string(a) +
           ", beyond 1e30 (scale the outline down)");
  auto section = [&](const char* what) {
    if (!f.NextDataLine(&line) || Tokens(line).Split(tok, 8) < 1)
      f.Fail(std::string("file ends before the number of ") + what);
    const int64_t m = f.ParseInt(tok[0], what);
    if (m < 0) f.Fail(std::string("the number of ") + what + " is negative");
    return m;
  };
  const int64_t segments = section("segments");
  for (int64_t i = 0; i < segments; ++i) {
    if (!f.NextDataLine(&line))
      f.Fail("file ends after " + std::to_string(i) + " of the " + std::to_string(segments) +
             " segments the header announces");
    if (Tokens(line).Split(tok, 8) < 3)
      f.Fail("segment " + std::to_string(i + 1) + " of the " + std::to_string(segments) +
             " announced: a segment line should read 'id first second'");
    for (int k = 1; k <= 2; ++k) {
      const int64_t v = f.ParseInt(tok[k], "a segment endpoint");
      if (v < base || v >= base + n)
        f.Fail("segment endpoint " + std::to_string(v) + " is not one of the vertices " +
               std::to_string(base) + ".." + std::to_string(base + n - 1));
    }
  }
  const int64_t holes = section("holes");
  for (int64_t i = 0; i < holes; ++i) {
    if (!f.NextDataLine(&line))
      f.Fail("file ends after " + std::to_string(i) + " of the " + std::to_string(holes) +
             " holes the header announces");
    if (Tokens(line).Split(tok, 8) < 3) f.Fail("a hole line should read 'id x y'");
    const double x = f.ParseDouble(tok[1], "x"), y = f.ParseDouble(tok[2], "y");
    if (!std::isfinite(x) || !std::isfinite(y)) f.Fail("a hole coordinate is not finite");
  }
  return a;
}

std::string FixedArea(double a) {
  // Triangle reads -a digits and '.', so never exponent notation.
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12f", a);
  std::string s(buf);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

double CheckPoly(const std::string& poly_path) { return CheckPolyFile(poly_path); }

TriangulateResult TriangulatePoly(const std::string& poly_path, const std::string& prefix,
                                  const TriangulateOptions& opt) {
  const std::string exe = FindProgram(opt.program);
  if (exe.empty())
    throw EnvironmentError(
        opt.program,
        "cannot find the '" + opt.program +
            "' program (Shewchuk's Triangle). On Debian it is the package triangle-bin in the "
            "non-free component: run scripts/setup.sh as root, or add 'non-free' to an apt source, "
            "then 'apt-get update && apt-get install triangle-bin'.");
  if (opt.target_vertices < 3) throw std::runtime_error("the vertex target must be at least 3");
  const double box = CheckPolyFile(poly_path);

  const fs::path out_dir = fs::absolute(fs::path(prefix)).parent_path();
  fs::create_directories(out_dir);
  std::string tmpl = (out_dir / ".meshreuse-triangle-XXXXXX").string();
  if (!::mkdtemp(tmpl.data()))
    throw EnvironmentError(out_dir.string(), "cannot create a scratch folder");
  ScratchDir scratch{tmpl};
  fs::copy_file(poly_path, scratch.path / "shape.poly");

  TriangulateResult best;
  double best_err = std::numeric_limits<double>::infinity();
  const double quality = opt.min_angle;
  char qbuf[32];
  std::snprintf(qbuf, sizeof qbuf, "%g", quality);

  // Stage 1 calibrates at a smaller size when the target is large (each run costs ~ target).
  const int64_t calib = std::min<int64_t>(opt.target_vertices, 200000);
  bool full = calib == opt.target_vertices;
  int64_t goal = calib;
  double area = 0.6 * box / static_cast<double>(goal);
  std::vector<std::pair<double, double>> hist;  // (log area, log vertices) at the current goal
  TriangulateResult r;
  for (int run = 1; run <= opt.max_runs; ++run) {
    if (FixedArea(area) == "0" || !(area > 0))
      throw InputError(
          poly_path, 0,
          "too small to mesh to " + std::to_string(goal) + " vertices: its box's area is " +
              [&] {
                char b[32];
                std::snprintf(b, sizeof b, "%g", box);
                return std::string(b);
              }() +
              " and Triangle's area bound has 12 decimals (scale the outline up)");
    const std::string sw = std::string("-pPq") + qbuf + "a" + FixedArea(area) + "Q";
    const fs::path log = scratch.path / "triangle.log";
    const int rc = Run({exe, sw, "shape.poly"}, scratch.path, log);
    // Triangle's own "Error:" is about the outline (the file was checked above for what can be
    // checked here); a crash or a missing output is the environment's.
    const std::string said = Tail(log);
    if (rc == 1 && said.find("Error:") != std::string::npos) {
      std::string msg = said.substr(said.find("Error:") + 6);
      msg.erase(0, msg.find_first_not_of(" "));
      while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
      throw InputError(poly_path, 0, "Triangle refused it: " + msg.substr(0, 200));
    }
    if (rc != 0 || !fs::exists(scratch.path / "shape.1.node"))
      throw EnvironmentError("triangle " + sw + " " + poly_path,
                             "failed (exit " + std::to_string(rc) + "): " + said);
    const int64_t v = HeaderCount(scratch.path / "shape.1.node");
    if (v < 3 || HeaderCount(scratch.path / "shape.1.ele") == 0)
      throw InputError(poly_path, 0,
                       "Triangle made no triangles of it (do its holes cover the whole outline?)");
    r.runs = run;
    if (opt.progress)
      opt.progress("triangle " + sw + ": " + std::to_string(v) + " vertices (goal " +
                   std::to_string(goal) + (full ? "" : ", calibrating") + ")");
    const double err = std::fabs(static_cast<double>(v) / goal - 1.0);
    if (full && err < best_err) {
      best_err = err;
      best.vertices = v;
      best.triangles = HeaderCount(scratch.path / "shape.1.ele");
      best.max_area = area;
      best.switches = sw;
      fs::rename(scratch.path / "shape.1.node", scratch.path / "best.node");
      fs::rename(scratch.path / "shape.1.ele", scratch.path / "best.ele");
    }
    if (err <= opt.tolerance || (!full && err <= 0.05)) {
      if (full) break;
      // Scale up from the calibration run, assuming vertices ~ 1 / area.
      area *= static_cast<double>(v) / static_cast<double>(opt.target_vertices);
      goal = opt.target_vertices;
      full = true;
      hist.clear();
      continue;
    }
    hist.emplace_back(std::log(area), std::log(static_cast<double>(v)));
    double slope = -1.0;
    if (hist.size() >= 2) {
      const auto& p = hist[hist.size() - 2];
      const auto& q = hist.back();
      if (q.first != p.first) slope = (q.second - p.second) / (q.first - p.first);
      slope = std::clamp(slope, -1.5, -0.3);
    }
    area *=
        std::exp((std::log(static_cast<double>(goal)) - std::log(static_cast<double>(v))) / slope);
  }
  if (!(best_err <= opt.accept))
    throw UsageError("--vertices " + std::to_string(opt.target_vertices) + ": could not mesh " +
                     poly_path + " to that many vertices within " +
                     std::to_string(static_cast<int>(opt.accept * 100)) + "% in " +
                     std::to_string(r.runs) + " Triangle runs (closest: " +
                     (best.vertices ? std::to_string(best.vertices) : std::string("none")) +
                     "); its outline needs more vertices than that");
  best.runs = r.runs;
  best.node_file = prefix + ".node";
  best.ele_file = prefix + ".ele";
  fs::rename(scratch.path / "best.node", best.node_file);
  fs::rename(scratch.path / "best.ele", best.ele_file);
  return best;
}

}  // namespace meshreuse
