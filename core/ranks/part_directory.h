// Who owns what after a distributed partition (issue 23, ../shared/scale-out.md 3c): a partitioner
// such as PT-Scotch returns, on each rank, the parts of that rank's range of ids (RangeFirst); no
// rank holds the whole partition. The range is a directory: a rank learns the ids of its own part
// by one all-to-all (each rank sends every id of its range to the id's part), and the owners of
// its ghosts by asking the ranks whose ranges hold them (one request and one answer per rank
// asked). Memory per rank: its range's parts, its part's ids, its ghosts; never one entry per
// vertex of the mesh. Over any transport (halo_smoother.h): MPI's or threads'.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ranks/halo_smoother.h"

namespace meshreuse {

// Every rank calls each at once. `part` holds the parts of this rank's range of a mesh of
// `vertices` vertices, ids [RangeFirst(rank), RangeFirst(rank + 1)).
// The ids whose part is this rank, increasing.
std::vector<int64_t> GatherOwnedIds(Communicator& tx, int64_t vertices,
                                    const std::vector<int32_t>& part);
// The parts of `ids` (increasing; this rank's ghosts), from the ranks whose ranges hold them.
std::vector<int32_t> LookUpParts(Communicator& tx, int64_t vertices,
                                 const std::vector<int32_t>& part, const std::vector<int64_t>& ids);
// Every vertex's part on every rank, by id (a mesh that fits one node, read whole by every rank).
std::vector<int32_t> AllParts(Communicator& tx, int64_t vertices, const std::vector<int32_t>& part);

// The exchange under them (Communicator::AllToAll of the values' bytes): out[q] goes to rank q;
// returns what each rank sent this one, by rank.
std::vector<std::vector<int64_t>> AllToAll(Communicator& tx,
                                           const std::vector<std::vector<int64_t>>& out);

}  // namespace meshreuse
