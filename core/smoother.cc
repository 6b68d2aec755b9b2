// Non-template parts of the smoother: names of the update modes.
#include "core/smoother.h"

#include <stdexcept>

namespace meshreuse {

const char* UpdateModeName(UpdateMode m) {
  return m == UpdateMode::kJacobi ? "jacobi" : "gauss-seidel";
}

UpdateMode ParseUpdateMode(const std::string& s) {
  if (s == "gs" || s == "gauss-seidel") return UpdateMode::kGaussSeidel;
  if (s == "jacobi") return UpdateMode::kJacobi;
  throw std::invalid_argument("unknown update mode '" + s + "' (expected gauss-seidel or jacobi)");
}

}  // namespace meshreuse
