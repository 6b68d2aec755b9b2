// What every result folder records about how it was made (run.json): the command line, the
// machine, the git revision the binary was built from, and a timestamp. A tiny JSON writer keeps
// the output valid without a JSON library.
#pragma once

#include <string>
#include <vector>

namespace meshreuse {

std::string JsonString(const std::string& s);  // quoted and escaped
std::string JsonNumber(double v);  // shortest round-trip form (integers in full); null for NaN/inf

// {"hostname":..., "cpu":..., "cores":..., "os":..., "caches": {"L1d": "48K", ...}, "compiler":...}
std::string MachineJson();
// The git revision of the sources this binary was built from, taken at build time, with
// "-dirty" when they differed from it ("unknown" outside a git checkout).
std::string GitRevision();
// "meshreuse 0.1.0 (git 4b00722c1d2e, Release, GNU 12.2.0)"
std::string VersionString();
// {"version", "git_revision", "git_dirty", "compiler", "compiler_version", "build_type", "flags"}
std::string BuildJson();
std::string UtcTimestamp();  // 2026-11-22T10:00:00Z
std::string CommandLineJson(const std::vector<std::string>& argv);

}  // namespace meshreuse
