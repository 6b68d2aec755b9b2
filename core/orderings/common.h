// Helpers shared by several orderings.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh.h"

namespace meshreuse::orderings {

// Breadth-first visit order over all vertices: from vertex 0, neighbours in increasing id, each
// further component from its lowest unvisited id. Used by bfs, rbfs and wave-blocks; `parent`, if
// given, gets each vertex's enqueuer (-1 for a component's root).
std::vector<int32_t> BfsVisitOrder(const Mesh& m, std::vector<int32_t>* parent = nullptr);

// `ids` stably sorted by key[id] (finite keys). One counting-sort pass into n/8 buckets by
// floor((k - min) / (max - min) * (n/8 - 1)) -- monotone in k, because IEEE operations round
// monotonically -- then an exact stable sort inside each bucket. O(n) for keys spread like
// qualities or curve indices; a bucket holding many distinct keys falls back to std::stable_sort.
std::vector<int32_t> StableSortByKey(const std::vector<int32_t>& ids,
                                     const std::vector<double>& key);

// The v2v rows with each row sorted by (key, id): "the neighbours of v by increasing key" is row v
// of the result (offsets m.v2v.off). Rows are short and in increasing id, so an insertion sort on
// the key keeps ties by id.
std::vector<int32_t> RowsByKey(const Mesh& m, const std::vector<double>& key);

// Vertices sorted by index(gx, gy) of their position on a 2^16 x 2^16 grid laid over the bounding
// box (each axis scaled independently), ties by id: hilbert and morton.
std::vector<int32_t> SortAlongCurve(const Mesh& m, uint64_t (*index)(uint32_t, uint32_t));

// A cache-sized argument in bytes (metis:BYTES, wave-blocks:BYTES), K/M suffixes; "" gives
// `dflt`. Throws UsageError naming `name`.
uint64_t ParseCacheBytes(const std::string& arg, uint64_t dflt, const char* name);
inline void CheckMetisPartBytes(const std::string& arg) { ParseCacheBytes(arg, 1, "metis"); }
inline void CheckMetisWaveBytes(const std::string& arg) { ParseCacheBytes(arg, 1, "metis-wave"); }
// wave-blocks's argument BLOCK[/BAND] in bytes: (32 KiB, 128 KiB) by default, BAND 4 x BLOCK
// when not given. Throws UsageError.
std::pair<uint64_t, uint64_t> ParseWaveBlocks(const std::string& arg);
inline void CheckWaveBlockBytes(const std::string& arg) { ParseWaveBlocks(arg); }

// What the sweep reads per vertex on average: coordinates, both adjacency rows and their offsets,
// the triangles' corners, weights and qualities, the interior list (about 66 bytes on a 2D mesh).
double SweepBytesPerVertex(const Mesh& m);

// wave-blocks with its sizes in vertices (core/orderings/wave_blocks.cc defines it): new -> old.
std::vector<int32_t> WaveBlocksOrder(const Mesh& m, int64_t block_vertices, int64_t band_vertices);

// METIS k-way parts whose sweep data fit part_bytes (metis.cc): part[v] in [0, *parts), or empty
// (and *parts = 1) when one part holds the mesh.
std::vector<int32_t> CacheSizedParts(const Mesh& m, uint64_t part_bytes, uint64_t seed,
                                     int32_t* parts);

// The non-empty cells of a uniform grid whose cells hold about part_bytes of sweep data
// (grid_wave.cc): part[v] in [0, *parts), or empty (and *parts = 1) when one cell would do.
std::vector<int32_t> GridParts(const Mesh& m, uint64_t part_bytes, int32_t* parts);
inline void CheckGridWaveBytes(const std::string& arg) { ParseCacheBytes(arg, 1, "grid-wave"); }

// Parts (part[v] in [0, parts)): their members (part p's are members[first[p], first[p + 1]), by
// ascending id) and their order, a BFS over the part graph from vertex 0's part, neighbour parts by
// increasing number, further components from the lowest unvisited part (metis, metis-wave).
struct PartLayout {
  std::vector<int64_t> first;
  std::vector<int32_t> members, order;
};
PartLayout LayOutParts(const Mesh& m, const std::vector<int32_t>& part, int32_t parts);

// Parts (part[v] in [0, parts)) laid out in BFS order over the part graph, each part's vertices
// by a wavefront that continues from the parts placed before it (core/orderings/metis_wave.cc).
std::vector<int32_t> WaveThroughParts(const Mesh& m, const std::vector<int32_t>& part,
                                      int32_t parts);

}  // namespace meshreuse::orderings
