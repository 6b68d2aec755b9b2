// Small pieces the subcommands share: loading a mesh with its warnings and progress, writing a
// text file atomically, splitting comma lists, the run.json header.
#pragma once

#include <string>
#include <vector>

#include "cli/progress.h"
#include "core/mesh.h"

namespace meshreuse::cli {

Mesh LoadMesh(const std::string& path, const Progress& progress);
void WriteText(const std::string& path, const std::string& text);
std::vector<std::string> SplitList(const std::string& s);  // "a,b,,c" -> {a, b, c}
// Throws a usage error (exit 2) for an empty list or a name the ordering registry does not know,
// before any work is done.
void CheckOrderings(const std::vector<std::string>& specs);
// The fields every run.json starts with: tool, command, git revision, time, machine.
std::string RunJsonHeader(const std::string& tool);

}  // namespace meshreuse::cli
