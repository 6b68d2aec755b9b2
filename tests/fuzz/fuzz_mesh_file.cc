// libFuzzer harness: a distributed mesh file (core/mesh_file.h). The first byte chooses whether
// the rest is read as it is (the hashes must then catch any change) or with fresh hashes
// (RehashMeshFile), so the fuzzer reaches the topology checks behind them. The whole-file reader
// and every rank's read at P = 1..3 run; what a reader accepts must build a mesh, pass its own
// checks (every rank's triangle and row counts add up, as CheckRankShares demands) and lay out.
#include <string>
#include <vector>

#include "core/mesh_file.h"
#include "core/ranks/partition.h"
#include "core/ranks/rank_neighbourhood.h"
#include "core/ranks/rank_part.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace meshreuse;
  if (size < 1) return 0;
  std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] & 1) bytes = RehashMeshFile(std::move(bytes));
  fuzz::MemFile f(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  try {
    RawMesh raw = ReadMeshFileRaw(f.path());
    {
      const Mesh m = BuildMesh(RawMesh{raw.xy, raw.tri, f.path(), f.path(), {}, {}, {}, {}});
      CheckMeshFileTopology(f.path(), m);
    }
    fuzz::Exercise(std::move(raw));
  } catch (const InputError&) {
  }
  int64_t vertices = -1;
  try {
    vertices = MeshFile(f.path()).vertices();
  } catch (const InputError&) {
  }
  for (int32_t P = 1; P <= 3; ++P)
    for (bool scattered : {false, true}) try {
        if (scattered && (vertices < P || vertices > (1 << 20))) continue;
        auto part_of = [P](int64_t v) { return static_cast<int32_t>((v * 2654435761u >> 5) % P); };
        const GhostOwners owners = [&](const std::vector<int64_t>& g) {
          std::vector<int32_t> q;
          for (int64_t v : g) q.push_back(part_of(v));
          return q;
        };
        std::vector<RankShare> shares;
        std::vector<RankNeighbourhood> nbs;
        for (int32_t r = 0; r < P; ++r) {
          if (!scattered) {
            nbs.push_back(ReadRankNeighbourhood(f.path(), r, P));
          } else {
            ReadRangeGraphRows(f.path(), r, P);
            std::vector<int64_t> owned;
            for (int64_t v = 0; v < vertices; ++v)
              if (part_of(v) == r) owned.push_back(v);
            nbs.push_back(ReadPartNeighbourhood(f.path(), r, P, owned, owners));
          }
          shares.push_back(ShareOf(nbs.back()));
        }
        int32_t colours = 0;
        const std::vector<int32_t> colour =
            GreedyPartColouring(CheckRankShares(f.path(), shares), &colours);
        for (RankNeighbourhood& nb : nbs) BuildRankPart(std::move(nb), colour, "bfs");
      } catch (const InputError&) {
      } catch (const UsageError&) {  // more ranks than vertices
      }
  return 0;
}
