// What a runner says while it works: progress lines (silenced by --quiet) and warnings about the
// input (dropped vertices, skipped elements), which a caller shows even when progress is silent.
// Runners never print; the CLI decides where these go (stderr).
#pragma once

#include <functional>
#include <string>

namespace meshreuse {

struct Log {
  std::function<void(const std::string&)> progress, warn;
  void Say(const std::string& s) const {
    if (progress) progress(s);
  }
  void Warn(const std::string& s) const {
    if (warn) warn(s);
  }
};

}  // namespace meshreuse
