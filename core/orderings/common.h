// Helpers shared by several orderings.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace meshreuse::orderings {

// Breadth-first visit order over all vertices: from vertex 0, neighbours in increasing id, each
// further component from its lowest unvisited id. Used by bfs and rbfs.
std::vector<int32_t> BfsVisitOrder(const Mesh& m);

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

// metis's argument: bytes per part, K/M suffixes; "" gives 256 KiB. Throws UsageError.
uint64_t ParseMetisPartBytes(const std::string& arg);
inline void CheckMetisPartBytes(const std::string& arg) { ParseMetisPartBytes(arg); }

}  // namespace meshreuse::orderings
