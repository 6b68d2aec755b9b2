// What every result folder records about how it was made (run.json), written with nlohmann::json:
// the tool and its command line, the configuration (with the seed of every seeded ordering), the
// machine (CPU, cores, caches, OS, load), the build (git revision taken at build time, dirty flag,
// compiler, flags), and the UTC time. One writer for every command (RunJson), so every run.json
// has the same top-level fields.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/orderings/registry.h"

namespace meshreuse {

using Json = nlohmann::ordered_json;

// {"hostname", "cpu", "cores", "os", "caches": {"L1d": "48K", ...}, "compiler"}
Json MachineJson();
// The git revision of the sources this binary was built from, taken at build time, with
// "-dirty" when they differed from it ("unknown" outside a git checkout).
std::string GitRevision();
// "meshreuse 0.1.0 (git 4b00722c1d2e, Release, GNU 12.2.0)"
std::string VersionString();
// {"version", "git_revision", "git_dirty", "compiler", "compiler_version", "build_type", "flags"}
Json BuildJson();
// {label: seed} of the seeded orderings among `specs` (run.json's "ordering_seeds").
Json OrderingSeedsJson(const std::vector<OrderingSpec>& specs, uint64_t seed);
// The specs as given (run.json's "orderings").
std::vector<std::string> OrderingTexts(const std::vector<OrderingSpec>& specs);
// This process's peak resident memory (getrusage), bytes.
uint64_t PeakRssBytes();
std::string UtcTimestamp();  // 2026-11-22T10:00:00Z

// The whole run.json: {"tool", "command", "git_revision", "build", "time_utc", "machine",
// "configuration", ...extra}. `extra`'s fields follow in their order.
Json RunJson(const std::string& tool, const std::vector<std::string>& command_line,
             const Json& configuration, const Json& extra = Json::object());
// Its text, as written (two-space indent, a final newline).
std::string RunJsonText(const Json& run);

}  // namespace meshreuse
