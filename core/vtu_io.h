// VTK XML unstructured grids, ParaView's native format: FILE.vtu (one grid of triangles) and
// FILE.pvtu (a partitioned grid: one .vtu piece per rank). Data is "appended" raw binary, little
// endian, with VTK's UInt64 header; where zlib is built in (VtuCompressed) every array is
// compressed in blocks of about 1 MiB at zlib level 1, VTK's vtkZLibDataCompressor layout
// ([blocks, block size, last block's size or 0, each block's compressed size], then the blocks).
// Level 1: on smoothed meshes it compresses coordinates and connectivity as well as level 6
// within 1% and 4x faster. Blocks are compressed in parallel (OpenMP), a few per thread at a
// time, and written as they come; the XML header, which names every array's offset, is written
// first with room for the longest offsets and rewritten in place once they are known (padded
// with spaces between elements). Only an output that cannot seek (a
// pipe) holds the compressed arrays in memory until the header can be written.
// Reference: VTK's file formats (docs.vtk.org, "VTK File Formats", XML and Parallel File
// Formats); ghosts follow vtkDataSetAttributes: an array "vtkGhostType" (UInt8) with 1 marking a
// duplicate point or cell owned by another piece.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace meshreuse {

enum class VtuType { kUInt8, kInt32, kInt64, kFloat32, kFloat64 };

// One data array: `tuples` tuples of `components` values of `type`. `fill(first, count, out)`
// writes tuples [first, first + count) to `out` (the writer asks block by block, so no array need
// be copied whole: coordinates given as x, y pairs are widened to x, y, 0 as they are written).
struct VtuArray {
  std::string name;
  VtuType type = VtuType::kFloat64;
  int components = 1;
  int64_t tuples = 0;
  std::function<void(int64_t first, int64_t count, void* out)> fill;
};

// An array read straight from memory (T: uint8_t, int32_t, int64_t, float or double).
template <class T>
VtuArray VtuArrayOf(std::string name, const T* data, int64_t tuples, int components = 1);

struct VtuGrid {
  int64_t points = 0;
  const double* xy = nullptr;    // 2 per point; written as x, y, 0
  int64_t cells = 0;             // triangles
  const int32_t* tri = nullptr;  // 3 corners per triangle, 0-based point indices
  std::vector<VtuArray> point_data, cell_data;
  std::string global_ids;  // a point array VTK takes as global ids ("": none)
};

bool VtuCompressed();  // whether .vtu arrays are zlib-compressed (zlib found at build time)

// Writes the grid through core/output_file.h (a temporary renamed when complete). Throws
// std::invalid_argument when an array's tuple count is not its grid's.
void WriteVtu(const VtuGrid& g, const std::string& path);
// A partitioned grid: `pieces` (paths relative to the .pvtu's folder), each a .vtu with `like`'s
// arrays; GhostLevel 1 (each piece carries one layer of ghost cells, marked vtkGhostType).
void WritePvtu(const std::string& path, const std::vector<std::string>& pieces,
               const VtuGrid& like);

}  // namespace meshreuse
