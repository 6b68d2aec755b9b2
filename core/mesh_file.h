// The distributed mesh file (FILE.mrm, issue 23; ../shared/scale-out.md 3c): one binary file that
// any number of ranks read, each only its own range of vertices and their ghost ring, with pread.
// Global ids are implicit (the position in the file); a file written by `meshreuse mesh convert
// IN -o OUT.mrm` stores its vertices in Hilbert order and its triangles stably by smallest corner,
// so contiguous ranges of ids are the Hilbert-range partition (partition.h) and a rank's triangles
// are nearly one contiguous run. A refined file in the pieces layout (refine.h, written by many
// ranks at once) keeps blocks of coarse triangles instead: readers need no particular order.
// Layout, little-endian, every section starting on 8 bytes:
//   header (128 bytes): magic "MRMESH1\n", u32 version (1), u32 block bytes (4096), i64 vertices
//     V, i64 triangles T, u64 content id, 80 zero bytes, u64 hash of the 120 bytes before it;
//   xy       V x 2 f64          coordinates;
//   boundary V x u8             1 on the topological boundary (what a rank cannot compute for its
//                               ghosts: their triangles are not all on the rank);
//   v2t_off  (V + 1) x i64      rows of the vertex -> triangle adjacency, v2t_off[V] = 3T;
//   v2t      3T x i32           each vertex's triangles, increasing id;
//   tri      T x 3 x i32        corners (orientation kept);
//   blocks   one u64 hash per 4 KiB block of the bytes from the end of the header to the start
//            of this table (the last block short);
//   pages    one u64 hash per page of 512 entries of the block table (the last page short).
// The content id hashes V, T and the page table: a rank reads the page table whole (8 bytes per
// 2 MiB of mesh: 190 KiB at 10^9 vertices) and only the pages of the block table it needs, so
// what it reads is its share of the file, whatever the size of the whole table.
// Checks: a reader refuses (InputError naming the file and byte offset or block) another magic or
// version, a damaged header, a size other than the header's sections add up to (truncated or
// trailing bytes), a block table that is not the content id's, and every block whose bytes it uses
// and whose hash differs: each rank verifies what it reads, so every byte of a distributed read is
// verified by some rank. The topology the boundary flags and v2t rows claim is checked by every
// reader: a rank's (rank_neighbourhood.h) for its range, the whole-file reader against the mesh
// it builds from xy and tri (CheckMeshFileTopology).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh.h"

namespace meshreuse {

inline constexpr uint32_t kMeshFileVersion = 1;
inline constexpr uint32_t kMeshFileBlock = 4096;
inline constexpr int64_t kMeshFileHeader = 128;
inline constexpr int64_t kMeshFilePage = 512;  // block hashes per page of the block table

// FILE.mrm: the path names a mesh file.
bool IsMeshFilePath(const std::string& path);
// The layout `mesh convert` and `mesh refine` give a mesh file: vertices in Hilbert order,
// triangles stably by smallest corner, so ranges of ids are the Hilbert-range partition.
void LayOutForRanks(Mesh* m);

// Writes `m` as stored (callers lay it out first: `mesh convert` in Hilbert order). Atomic, as
// every output (output_file.h).
void WriteMeshFile(const Mesh& m, const std::string& path);
// The whole file as a RawMesh (serial commands read FILE.mrm like any mesh).
RawMesh ReadMeshFileRaw(const std::string& path);
// The stored boundary flags and v2t rows against the mesh built from the file's xy and triangles
// (ReadMesh calls it): a file a distributed read would refuse is refused by every reader.
// InputError naming the first disagreement.
void CheckMeshFileTopology(const std::string& path, const Mesh& m);

// The checked reader. Sections by element; every read verifies the blocks it touches.
class MeshFile {
 public:
  explicit MeshFile(const std::string& path);  // opens and checks header, size and block table
  ~MeshFile();
  MeshFile(const MeshFile&) = delete;
  MeshFile& operator=(const MeshFile&) = delete;

  enum Section { kXy, kBoundary, kV2tOff, kV2t, kTri, kSections };
  int64_t vertices() const { return vertices_; }
  int64_t triangles() const { return triangles_; }
  uint64_t content_id() const { return content_id_; }
  const std::string& path() const { return path_; }
  int64_t ElementBytes(Section s) const;
  int64_t Elements(Section s) const;
  // Elements [first, first + count) of section `s` into `out` (ElementBytes(s) * count bytes).
  void Read(Section s, int64_t first, int64_t count, void* out);
  // Elements `at` (increasing, may repeat) of section `s`, one after another into `out`: each block
  // is read once however many of the elements lie in it.
  void ReadAt(Section s, const std::vector<int64_t>& at, void* out);
  // Runs [first[i], end[i]) of elements of section `s` (starts non-decreasing, runs may be empty),
  // one after another into `out`: blocks shared by neighbouring runs are read once (a rank's
  // scattered part, read run by run of consecutive ids).
  void ReadRuns(Section s, const std::vector<int64_t>& first, const std::vector<int64_t>& end,
                void* out);
  uint64_t bytes_read() const { return bytes_read_; }

 private:
  int64_t Offset(Section s) const { return offset_[s]; }
  // Reads file bytes [a, b) into `out`, verifying every block they touch (each block once).
  void ReadChecked(int64_t a, int64_t b, char* out);
  void Fail(int64_t offset, const std::string& problem) const;
  void PreadAll(char* out, int64_t n, int64_t at);
  void ReadSpans(Section s, size_t count,
                 const std::function<std::pair<int64_t, int64_t>(size_t)>& span, char* out);
  uint64_t BlockHash(int64_t k);

  struct Fd {  // closed by its destructor, also when the constructor throws
    int fd = -1;
    ~Fd();
  };
  std::string path_;
  Fd fd_;
  int64_t vertices_ = 0, triangles_ = 0, file_bytes_ = 0, data_end_ = 0;
  int64_t offset_[kSections + 1] = {};
  uint64_t content_id_ = 0;
  int64_t blocks_ = 0;
  std::vector<uint64_t> page_hash_;          // the page table, read whole
  std::vector<std::vector<uint64_t>> page_;  // pages of the block table, read when needed
  std::vector<bool> verified_;               // blocks
  std::vector<char> scratch_;
  uint64_t bytes_read_ = 0;
};

// The hash of one block (exposed for the tests that damage a file and mend its table).
uint64_t MeshFileBlockHash(const char* p, size_t n);
// The hash of each page of a block table (kMeshFilePage entries, the last page short).
std::vector<uint64_t> MeshFilePageHashes(const std::vector<uint64_t>& block_table);
// The content id of a page table (what the header stores).
uint64_t MeshFileContentId(int64_t vertices, int64_t triangles,
                           const std::vector<uint64_t>& page_hashes);
// The hash of a header's first 120 bytes.
uint64_t MeshFileHeaderHash(const char* header);
// Writing a smoothed mesh file from many ranks at once, no rank holding the mesh (the distributed
// smoother's -o FILE.mrm): the output starts as a copy of the input (each rank copies a byte
// range), each rank then writes its owned range of coordinates, hashes a share of the coordinate
// section's blocks, and one rank writes those hashes into the table and renews the page table,
// content id and header hash. Between the steps every rank must have finished the previous one.
// Bytes [a, b) of `from` to the same place in `to` (which exists; nothing truncated).
void CopyFileBytes(const std::string& from, const std::string& to, int64_t a, int64_t b);
// Coordinates of vertices `ids` (increasing; any set: a rank's part), two per id in `xy`, into the
// mesh file at `path`, one write per run of consecutive ids.
void WriteMeshFileCoordinates(const std::string& path, const std::vector<int64_t>& ids,
                              const std::vector<double>& xy);
// The blocks holding the coordinates of `vertices` vertices: [0, CoordinateBlocks(vertices)).
int64_t CoordinateBlocks(int64_t vertices);
// Fresh hashes of blocks [first, end) of the file at `path` (its header read for the sizes).
std::vector<uint64_t> HashMeshFileBlocks(const std::string& path, int64_t first, int64_t end);
// Writes `hashes` over blocks [0, hashes.size()) of the table, then the page table, content id and
// header hash; returns the content id.
uint64_t FinishMeshFile(const std::string& path, const std::vector<uint64_t>& hashes);

// Writing a new mesh file from many ranks at once, no rank holding the mesh (`meshreuse-mpi
// refine`): one rank creates the file at its full size with the sizes in its header
// (CreateMeshFile); every rank writes its range of every section (WriteMeshFileRange); once all
// have, each hashes a share of the blocks [0, MeshFileBlocks(V, T)) (HashMeshFileBlocks) and one
// rank writes the tables and header (FinishMeshFile).
struct MeshFileRange {
  int64_t first_vertex = 0, first_triangle = 0;
  std::vector<double> xy;         // 2 per vertex of the range
  std::vector<uint8_t> boundary;  // 1 per vertex of the range
  std::vector<int64_t> v2t_off;   // the range's row offsets (absolute), one more than its vertices
  std::vector<int32_t> v2t;       // the range's rows, from v2t_off.front()
  std::vector<int32_t> tri;       // 3 per triangle of the range
};
void CreateMeshFile(const std::string& path, int64_t vertices, int64_t triangles);
// The range's bytes at their places (the last range also writes v2t_off[V]); logic_error for a
// range that does not fit the sizes in the file's header.
void WriteMeshFileRange(const std::string& path, const MeshFileRange& r);
int64_t MeshFileBlocks(int64_t vertices, int64_t triangles);

// A file's bytes with fresh block, page and header hashes (for the tests and the fuzzer that damage
// a file and want the damage to reach the checks behind the hashes); bytes too short for the
// sizes their header announces come back unchanged.
std::string RehashMeshFile(std::string bytes);

}  // namespace meshreuse
