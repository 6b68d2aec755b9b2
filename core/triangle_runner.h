// Meshing a .poly outline with Shewchuk's Triangle (the external `triangle` program, Debian package
// triangle-bin) to a requested number of vertices. Triangle is run with -p (the outline and its
// holes), -q<angle> (minimum-angle quality constraint), -a<area> (maximum triangle area), -P (no
// output .poly) and -Q (quiet). The vertex count falls roughly as 1/area, so the area is found by a
// secant search on log(vertices) against log(area): first at a calibration size when the target is
// large, then at the target itself. Triangle's own vertex numbering is kept (it is ORI).
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "core/error.h"

namespace meshreuse {

struct TriangulateOptions {
  int64_t target_vertices = 0;
  double tolerance = 0.01;  // stop searching once within this relative error
  double accept = 0.03;     // fail unless the best run is within this relative error
  double min_angle = 20.0;  // Triangle's -q (its default is 20 degrees)
  int max_runs = 12;
  std::string program = "triangle";
  std::function<void(const std::string&)> progress;  // one line per Triangle run
};

struct TriangulateResult {
  int64_t vertices = 0;
  int64_t triangles = 0;
  double max_area = 0;
  int runs = 0;
  std::string switches;  // the Triangle switches of the run that was kept
  std::string node_file, ele_file;
};

// Checks a .poly before Triangle sees it (InputError naming the line): vertices in the file, at
// least 3, finite, spanning an area in (0, 1e30); segments and holes as many as announced, each
// segment between two of the vertices. Returns the vertices' bounding-box area.
double CheckPoly(const std::string& poly_path);

// Meshes `poly_path` and writes PREFIX.node and PREFIX.ele (creating PREFIX's folder). Throws
// EnvironmentError when `triangle` is missing or fails, InputError for a .poly that Triangle
// cannot mesh (CheckPoly's reasons; Triangle's own refusals; holes covering everything), and
// std::runtime_error when the count cannot be reached (e.g. fewer vertices than the outline has).
TriangulateResult TriangulatePoly(const std::string& poly_path, const std::string& prefix,
                                  const TriangulateOptions& opt);

// Full path of `program` found on PATH (or as given when it has a '/'), or "" when absent.
std::string FindProgram(const std::string& program);

}  // namespace meshreuse
