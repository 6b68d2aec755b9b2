// The shape table; see shapes.h. Vertex and triangle counts are the paper's Table 4.
#include "core/shapes.h"

#include <cstdlib>

namespace meshreuse {

const std::vector<ShapeInfo>& Shapes() {
  static const std::vector<ShapeInfo> kShapes = {
      {"carabiner", 328082, 652920, "pear-shaped ring (one hole)"},
      {"crake", 298898, 595638, "bird outline with beak, tail and legs; eye hole"},
      {"dialog", 306824, 611620, "speech bubble with a tail; three dot holes"},
      {"lake", 375288, 747676, "irregular lake shore; three island holes"},
      {"riverflow", 332699, 661615, "meandering river channel; two island holes"},
      {"ocean", 392674, 783040, "ocean below a wavy coastline; five island holes"},
      {"stress", 312763, 622868, "dog-bone tensile specimen with a central hole"},
      {"valve", 300985, 599368, "flange with a bore, six bolt holes and a key notch"},
      {"wrench", 386757, 771097, "open-end wrench with a ring end and hexagonal hole"},
  };
  return kShapes;
}

const ShapeInfo* FindShape(const std::string& name) {
  for (const ShapeInfo& s : Shapes())
    if (name == s.name) return &s;
  return nullptr;
}

std::string ShapeNames() {
  std::string s;
  for (const ShapeInfo& i : Shapes()) s += (s.empty() ? "" : ", ") + std::string(i.name);
  return s;
}

std::string ShapesDir() {
  if (const char* e = std::getenv("MESHREUSE_SHAPES")) return e;
  return MESHREUSE_SOURCE_DIR "/core/shapes";
}

}  // namespace meshreuse
