// Small pieces the subcommands share: loading a mesh with its warnings and progress, writing a
// text file atomically, splitting comma lists, the run.json header.
#pragma once

#include <string>
#include <vector>

#include "cli/options.h"
#include "cli/progress.h"
#include "core/mesh.h"
#include "core/permutation.h"

namespace meshreuse::cli {

Mesh LoadMesh(const std::string& path, const Progress& progress);
void WriteText(const std::string& path, const std::string& text);
// Before any work: an output file's folder must exist and be a folder (po::error otherwise), so a
// long run does not fail at its last step.
void CheckWritable(const std::string& path);
// --json, --csv and --markdown exclude each other: po::error when more than one is given.
void CheckOneFormat(const po::variables_map& vm);
// An output folder, before any work: made if missing (with its parents); po::error if it or an
// ancestor is a file, it cannot be written, or (must_be_empty) it already holds files.
void PrepareOutDir(const std::string& dir, bool must_be_empty = false);
std::vector<std::string> SplitList(const std::string& s);
// "1,2,4" -> {1, 2, 4}: po::error for a non-number, a count outside 1..1024 or an empty list.
std::vector<int> ParseThreadList(const std::string& s);  // "a,b,,c" -> {a, b, c}
// Throws a usage error (exit 2) for an empty list or a name the ordering registry does not know,
// before any work is done.
void CheckOrderings(const std::vector<std::string>& specs);
// True for a mesh path (.node, .ele, .msh, or a prefix with a .node beside it), false for traces.
bool IsMesh(const std::string& path);

// --triangle-order sorted|file, the same text on every command that lays a mesh out.
void AddTriangleOrderOption(po::options_description& desc, std::string* value);
TriangleOrder TriangleOrderOption(const std::string& value);  // po::error on a bad name
// The mesh at `path` laid out in `ordering` (ori included) with the triangle policy; the ordering
// name must have been checked (CheckOrderings).
Mesh LayOut(const std::string& path, const std::string& ordering, uint64_t seed,
            TriangleOrder triangles, const Progress& progress);

// The fields every run.json starts with: tool, command, git revision, time, machine.
std::string RunJsonHeader(const std::string& tool);

}  // namespace meshreuse::cli
