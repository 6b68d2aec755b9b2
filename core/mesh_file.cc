// The distributed mesh file: writer, checked reader, whole-file reader; see mesh_file.h.
#include "core/mesh_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <functional>

#include "core/error.h"
#include "core/mix.h"
#include "core/orderings/registry.h"
#include "core/output_file.h"
#include "core/permutation.h"
#include "core/progress.h"

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "mesh_file.cc writes and reads its integers as stored: little-endian hosts only"
#endif

namespace meshreuse {

namespace {

constexpr char kMagic[8] = {'M', 'R', 'M', 'E', 'S', 'H', '1', '\n'};
constexpr int64_t kMaxId = INT32_MAX;  // ids are int32 in memory

int64_t Pad8(int64_t n) { return (n + 7) / 8 * 8; }

// Section starts for V vertices and T triangles (V, T <= 2^31: no product overflows).
void Layout(int64_t v, int64_t t, int64_t* off) {
  off[MeshFile::kXy] = kMeshFileHeader;
  off[MeshFile::kBoundary] = off[MeshFile::kXy] + 16 * v;
  off[MeshFile::kV2tOff] = off[MeshFile::kBoundary] + Pad8(v);
  off[MeshFile::kV2t] = off[MeshFile::kV2tOff] + 8 * (v + 1);
  off[MeshFile::kTri] = off[MeshFile::kV2t] + Pad8(12 * t);
  off[MeshFile::kSections] = off[MeshFile::kTri] + Pad8(12 * t);
}

int64_t BlockCount(int64_t data_end) {
  return (data_end - kMeshFileHeader + kMeshFileBlock - 1) / kMeshFileBlock;
}
int64_t Pages(int64_t blocks) { return (blocks + kMeshFilePage - 1) / kMeshFilePage; }

template <class T>
T Load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

namespace {

// A descriptor closed on every path out.
struct OpenFd {
  int fd;
  OpenFd(const std::string& path, int flags) : fd(::open(path.c_str(), flags | O_CLOEXEC)) {
    if (fd < 0) throw EnvironmentError(path, std::string("cannot open: ") + std::strerror(errno));
  }
  ~OpenFd() { ::close(fd); }
  OpenFd(const OpenFd&) = delete;
  OpenFd& operator=(const OpenFd&) = delete;
};

void PreadFully(int fd, char* p, int64_t n, int64_t at, const std::string& path) {
  for (int64_t got = 0; got < n;) {
    const ssize_t r = ::pread(fd, p + got, static_cast<size_t>(n - got), at + got);
    if (r <= 0) throw EnvironmentError(path, "cannot read back what was written");
    got += r;
  }
}

void PwriteFully(int fd, const char* p, int64_t n, int64_t at, const std::string& path) {
  for (int64_t put = 0; put < n;) {
    const ssize_t r = ::pwrite(fd, p + put, static_cast<size_t>(n - put), at + put);
    if (r <= 0) throw EnvironmentError(path, std::string("cannot write: ") + std::strerror(errno));
    put += r;
  }
}

// V and T from a header this process (or the copy it came from) wrote: only sizes are taken.
void Sizes(int fd, const std::string& path, int64_t* v, int64_t* t) {
  char h[kMeshFileHeader];
  PreadFully(fd, h, kMeshFileHeader, 0, path);
  *v = Load<int64_t>(h + 16), *t = Load<int64_t>(h + 24);
  if (*v < 1 || *v > kMaxId || *t < 1 || *t > kMaxId / 3)
    throw std::logic_error(path + ": not a mesh file this process wrote");
}

}  // namespace

void CopyFileBytes(const std::string& from, const std::string& to, int64_t a, int64_t b) {
  OpenFd in(from, O_RDONLY), out(to, O_WRONLY);
  std::vector<char> buf(size_t{1} << 22);
  for (int64_t at = a; at < b;) {
    const int64_t n = std::min<int64_t>(static_cast<int64_t>(buf.size()), b - at);
    PreadFully(in.fd, buf.data(), n, at, from);
    PwriteFully(out.fd, buf.data(), n, at, to);
    at += n;
  }
}

void WriteMeshFileCoordinates(const std::string& path, const std::vector<int64_t>& ids,
                              const std::vector<double>& xy) {
  if (xy.size() != 2 * ids.size())
    throw std::logic_error("WriteMeshFileCoordinates: two coordinates per vertex");
  OpenFd out(path, O_WRONLY);
  for (size_t i = 0; i < ids.size();) {  // one write per run of consecutive ids
    size_t j = i + 1;
    while (j < ids.size() && ids[j] == ids[j - 1] + 1) ++j;
    if (ids[i] < 0 || (i && ids[i] <= ids[i - 1]))
      throw std::logic_error("WriteMeshFileCoordinates: ids not increasing");
    PwriteFully(out.fd, reinterpret_cast<const char*>(xy.data() + 2 * i),
                static_cast<int64_t>(16 * (j - i)), kMeshFileHeader + 16 * ids[i], path);
    i = j;
  }
}

int64_t CoordinateBlocks(int64_t vertices) {
  return (16 * vertices + kMeshFileBlock - 1) / kMeshFileBlock;
}

std::vector<uint64_t> HashMeshFileBlocks(const std::string& path, int64_t first, int64_t end) {
  OpenFd f(path, O_RDONLY);
  int64_t v, t, off[MeshFile::kSections + 1];
  Sizes(f.fd, path, &v, &t);
  Layout(v, t, off);
  const int64_t data_end = off[MeshFile::kSections];
  std::vector<uint64_t> out;
  std::vector<char> block(kMeshFileBlock);
  for (int64_t k = first; k < end; ++k) {
    const int64_t a = kMeshFileHeader + k * kMeshFileBlock;
    const int64_t n = std::min<int64_t>(kMeshFileBlock, data_end - a);
    PreadFully(f.fd, block.data(), n, a, path);
    out.push_back(MeshFileBlockHash(block.data(), static_cast<size_t>(n)));
  }
  return out;
}

uint64_t FinishMeshFile(const std::string& path, const std::vector<uint64_t>& hashes) {
  OpenFd f(path, O_RDWR);
  int64_t v, t, off[MeshFile::kSections + 1];
  Sizes(f.fd, path, &v, &t);
  Layout(v, t, off);
  const int64_t end = off[MeshFile::kSections], blocks = BlockCount(end);
  if (static_cast<int64_t>(hashes.size()) > blocks)
    throw std::logic_error("FinishMeshFile: more hashes than blocks");
  PwriteFully(f.fd, reinterpret_cast<const char*>(hashes.data()),
              static_cast<int64_t>(8 * hashes.size()), end, path);
  // The page table from the whole block table, a page at a time.
  std::vector<uint64_t> pages, page;
  for (int64_t p = 0; p < blocks; p += kMeshFilePage) {
    page.resize(static_cast<size_t>(std::min<int64_t>(kMeshFilePage, blocks - p)));
    PreadFully(f.fd, reinterpret_cast<char*>(page.data()), 8 * static_cast<int64_t>(page.size()),
               end + 8 * p, path);
    pages.push_back(MeshFileBlockHash(reinterpret_cast<const char*>(page.data()), 8 * page.size()));
  }
  PwriteFully(f.fd, reinterpret_cast<const char*>(pages.data()),
              static_cast<int64_t>(8 * pages.size()), end + 8 * blocks, path);
  char h[kMeshFileHeader];
  PreadFully(f.fd, h, kMeshFileHeader, 0, path);
  const uint64_t id = MeshFileContentId(v, t, pages);
  std::memcpy(h + 32, &id, 8);
  const uint64_t hh = MeshFileHeaderHash(h);
  std::memcpy(h + 120, &hh, 8);
  PwriteFully(f.fd, h, kMeshFileHeader, 0, path);
  return id;
}

int64_t MeshFileBlocks(int64_t vertices, int64_t triangles) {
  int64_t off[MeshFile::kSections + 1];
  Layout(vertices, triangles, off);
  return BlockCount(off[MeshFile::kSections]);
}

void CreateMeshFile(const std::string& path, int64_t v, int64_t t) {
  if (v < 1 || v > kMaxId || t < 1 || t > kMaxId / 3)
    throw std::logic_error("CreateMeshFile: sizes out of range");
  int64_t off[MeshFile::kSections + 1];
  Layout(v, t, off);
  const int64_t end = off[MeshFile::kSections], blocks = BlockCount(end);
  OpenFd f(path, O_WRONLY);
  if (::ftruncate(f.fd, 0) != 0 || ::ftruncate(f.fd, end + 8 * blocks + 8 * Pages(blocks)) != 0)
    throw EnvironmentError(path, std::string("cannot size: ") + std::strerror(errno));
  char header[kMeshFileHeader] = {};  // content id and header hash: FinishMeshFile's
  std::memcpy(header, kMagic, 8);
  const uint32_t version = kMeshFileVersion, block = kMeshFileBlock;
  std::memcpy(header + 8, &version, 4);
  std::memcpy(header + 12, &block, 4);
  std::memcpy(header + 16, &v, 8);
  std::memcpy(header + 24, &t, 8);
  PwriteFully(f.fd, header, kMeshFileHeader, 0, path);
}

void WriteMeshFileRange(const std::string& path, const MeshFileRange& r) {
  OpenFd f(path, O_WRONLY);
  int64_t v, t, off[MeshFile::kSections + 1];
  {
    OpenFd in(path, O_RDONLY);
    Sizes(in.fd, path, &v, &t);
  }
  Layout(v, t, off);
  const int64_t n = static_cast<int64_t>(r.boundary.size()),
                nt = static_cast<int64_t>(r.tri.size());
  if (r.first_vertex < 0 || n > v - r.first_vertex || r.xy.size() != 2 * r.boundary.size() ||
      r.v2t_off.size() != r.boundary.size() + 1 || r.first_triangle < 0 || nt % 3 ||
      nt / 3 > t - r.first_triangle || r.v2t_off.front() < 0 ||
      r.v2t_off.back() - r.v2t_off.front() != static_cast<int64_t>(r.v2t.size()) ||
      r.v2t_off.back() > 3 * t)
    throw std::logic_error("WriteMeshFileRange: a range that does not fit the file");
  auto put = [&](const void* p, int64_t bytes, int64_t at) {
    if (bytes) PwriteFully(f.fd, static_cast<const char*>(p), bytes, at, path);
  };
  put(r.xy.data(), 16 * n, off[MeshFile::kXy] + 16 * r.first_vertex);
  put(r.boundary.data(), n, off[MeshFile::kBoundary] + r.first_vertex);
  const bool last = r.first_vertex + n == v;  // also writes v2t_off[V]
  put(r.v2t_off.data(), 8 * (n + last), off[MeshFile::kV2tOff] + 8 * r.first_vertex);
  put(r.v2t.data(), 4 * static_cast<int64_t>(r.v2t.size()),
      off[MeshFile::kV2t] + 4 * r.v2t_off.front());
  put(r.tri.data(), 4 * nt, off[MeshFile::kTri] + 12 * r.first_triangle);
}

std::string RehashMeshFile(std::string b) {
  if (b.size() < static_cast<size_t>(kMeshFileHeader)) return b;
  const int64_t v = Load<int64_t>(b.data() + 16), t = Load<int64_t>(b.data() + 24);
  if (v < 1 || v > kMaxId || t < 1 || t > kMaxId / 3) return b;
  int64_t off[MeshFile::kSections + 1];
  Layout(v, t, off);
  const int64_t end = off[MeshFile::kSections], blocks = BlockCount(end);
  if (static_cast<int64_t>(b.size()) != end + 8 * blocks + 8 * Pages(blocks)) return b;
  std::vector<uint64_t> table;
  for (int64_t a = kMeshFileHeader; a < end; a += kMeshFileBlock)
    table.push_back(MeshFileBlockHash(
        b.data() + a, static_cast<size_t>(std::min<int64_t>(end, a + kMeshFileBlock) - a)));
  const std::vector<uint64_t> pages = MeshFilePageHashes(table);
  std::memcpy(&b[end], table.data(), 8 * table.size());
  std::memcpy(&b[end + 8 * table.size()], pages.data(), 8 * pages.size());
  const uint64_t id = MeshFileContentId(v, t, pages);
  std::memcpy(&b[32], &id, 8);
  const uint64_t h = MeshFileHeaderHash(b.data());
  std::memcpy(&b[120], &h, 8);
  return b;
}

bool IsMeshFilePath(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".mrm") == 0;
}

void LayOutForRanks(Mesh* m) {
  ApplyPermutationInPlace(m, ComputeOrdering("hilbert", *m), TriangleOrder::kSorted);
}

uint64_t MeshFileBlockHash(const char* p, size_t n) {
  uint64_t h = Mix64(0x6D72626C6F636BULL ^ n);
  size_t i = 0;
  for (; i + 8 <= n; i += 8) h = Mix64(h ^ Load<uint64_t>(p + i));
  if (i < n) {
    uint64_t w = 0;
    std::memcpy(&w, p + i, n - i);
    h = Mix64(h ^ w ^ 0x8000000000000000ULL);
  }
  return h;
}

std::vector<uint64_t> MeshFilePageHashes(const std::vector<uint64_t>& block_table) {
  std::vector<uint64_t> pages;
  for (size_t a = 0; a < block_table.size(); a += kMeshFilePage)
    pages.push_back(MeshFileBlockHash(reinterpret_cast<const char*>(block_table.data() + a),
                                      8 * std::min<size_t>(kMeshFilePage, block_table.size() - a)));
  return pages;
}

uint64_t MeshFileContentId(int64_t vertices, int64_t triangles,
                           const std::vector<uint64_t>& page_hashes) {
  uint64_t h = Mix64(static_cast<uint64_t>(vertices) * 0x9E3779B97F4A7C15ULL ^
                     static_cast<uint64_t>(triangles));
  for (uint64_t b : page_hashes) h = Mix64(h ^ b) + 0x632BE59BD9B4E019ULL;
  return h;
}

uint64_t MeshFileHeaderHash(const char* header) { return MeshFileBlockHash(header, 120); }

void WriteMeshFile(const Mesh& m, const std::string& path) {
  const int64_t v = m.NumVertices(), t = m.NumTriangles();
  int64_t off[MeshFile::kSections + 1];
  Layout(v, t, off);
  static const char kZero[8] = {};
  // The sections as pieces in file order after the header, padding included.
  auto pieces = [&](const std::function<void(const char*, size_t)>& f) {
    auto put = [&](const void* p, int64_t n) {
      if (n) f(static_cast<const char*>(p), static_cast<size_t>(n));
      if (n % 8) f(kZero, static_cast<size_t>(8 - n % 8));
    };
    put(m.xy.data(), 16 * v);
    put(m.boundary.data(), v);
    put(m.v2t.off.data(), 8 * (v + 1));
    put(m.v2t.idx.data(), 12 * t);
    put(m.tri.data(), 12 * t);
  };
  // Pass 1: the block table, through a block-sized buffer.
  std::vector<uint64_t> table;
  std::vector<char> buf;
  buf.reserve(kMeshFileBlock);
  pieces([&](const char* p, size_t n) {
    while (n) {
      const size_t k = std::min<size_t>(n, kMeshFileBlock - buf.size());
      buf.insert(buf.end(), p, p + k);
      p += k, n -= k;
      if (buf.size() == kMeshFileBlock) {
        table.push_back(MeshFileBlockHash(buf.data(), buf.size()));
        buf.clear();
      }
    }
  });
  if (!buf.empty()) table.push_back(MeshFileBlockHash(buf.data(), buf.size()));
  char header[kMeshFileHeader] = {};
  std::memcpy(header, kMagic, 8);
  const uint32_t version = kMeshFileVersion, block = kMeshFileBlock;
  const std::vector<uint64_t> pages = MeshFilePageHashes(table);
  const uint64_t id = MeshFileContentId(v, t, pages);
  std::memcpy(header + 8, &version, 4);
  std::memcpy(header + 12, &block, 4);
  std::memcpy(header + 16, &v, 8);
  std::memcpy(header + 24, &t, 8);
  std::memcpy(header + 32, &id, 8);
  const uint64_t hh = MeshFileHeaderHash(header);
  std::memcpy(header + 120, &hh, 8);
  // Pass 2: the bytes.
  WriteAtomically(path, [&](std::FILE* f) {
    auto write = [&](const char* p, size_t n) {  // a short write: Commit's ferror reports it
      if (std::fwrite(p, 1, n, f) != n) throw EnvironmentError(path, "cannot write: short write");
    };
    write(header, sizeof header);
    pieces(write);
    write(reinterpret_cast<const char*>(table.data()), 8 * table.size());
    write(reinterpret_cast<const char*>(pages.data()), 8 * pages.size());
  });
}

MeshFile::MeshFile(const std::string& path) : path_(path) {
  fd_.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_.fd < 0) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_.fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw InputError(path, 0, "not a regular file (ranks read their ranges with pread)");
  file_bytes_ = st.st_size;
  char h[kMeshFileHeader];
  if (file_bytes_ < kMeshFileHeader)
    Fail(0, "truncated: " + std::to_string(file_bytes_) +
                " bytes, shorter than the 128-byte header of a meshreuse mesh file");
  PreadAll(h, sizeof h, 0);
  if (std::memcmp(h, kMagic, 8) != 0)
    Fail(0, "not a meshreuse mesh file (its first bytes are not \"MRMESH1\\n\")");
  if (Load<uint64_t>(h + 120) != MeshFileHeaderHash(h))
    Fail(120, "the header's hash does not match its bytes: the header is damaged");
  const uint32_t version = Load<uint32_t>(h + 8), block = Load<uint32_t>(h + 12);
  if (version != kMeshFileVersion)
    Fail(8, "version " + std::to_string(version) + ", this build reads version " +
                std::to_string(kMeshFileVersion));
  if (block != kMeshFileBlock)
    Fail(12,
         "block size " + std::to_string(block) + ", expected " + std::to_string(kMeshFileBlock));
  vertices_ = Load<int64_t>(h + 16);
  triangles_ = Load<int64_t>(h + 24);
  content_id_ = Load<uint64_t>(h + 32);
  if (vertices_ < 1 || vertices_ > kMaxId)
    Fail(16, std::to_string(vertices_) + " vertices: expected 1.." + std::to_string(kMaxId));
  if (triangles_ < 1 || triangles_ > kMaxId / 3)
    Fail(24, std::to_string(triangles_) + " triangles: expected 1.." + std::to_string(kMaxId / 3));
  for (int i = 40; i < 120; ++i)
    if (h[i] != 0) Fail(i, "a reserved header byte is not zero");
  Layout(vertices_, triangles_, offset_);
  data_end_ = offset_[kSections];
  blocks_ = BlockCount(data_end_);
  const int64_t pages = Pages(blocks_);
  const int64_t expected = data_end_ + 8 * blocks_ + 8 * pages;
  if (file_bytes_ != expected)
    Fail(file_bytes_ < expected ? file_bytes_ : expected,
         (file_bytes_ < expected ? "truncated: " : "trailing bytes: ") +
             std::to_string(file_bytes_) + " bytes, the header's " + std::to_string(vertices_) +
             " vertices and " + std::to_string(triangles_) + " triangles make " +
             std::to_string(expected));
  page_hash_.resize(static_cast<size_t>(pages));
  PreadAll(reinterpret_cast<char*>(page_hash_.data()), 8 * pages, data_end_ + 8 * blocks_);
  if (MeshFileContentId(vertices_, triangles_, page_hash_) != content_id_)
    Fail(data_end_ + 8 * blocks_,
         "the block table does not belong to this header's content id (a table from another "
         "mesh, or damaged)");
  page_.resize(static_cast<size_t>(pages));
  verified_.assign(static_cast<size_t>(blocks_), false);
}

void MeshFile::PreadAll(char* out, int64_t n, int64_t at) {
  int64_t got = 0;
  while (got < n) {
    const ssize_t r = ::pread(fd_.fd, out + got, static_cast<size_t>(n - got), at + got);
    if (r <= 0)
      Fail(at + got, std::string("read error: ") + (r < 0 ? std::strerror(errno) : "end of file"));
    got += r;
    ReportProgress(bytes_read_ + static_cast<uint64_t>(got), static_cast<uint64_t>(file_bytes_));
  }
  bytes_read_ += static_cast<uint64_t>(n);
}

uint64_t MeshFile::BlockHash(int64_t k) {
  std::vector<uint64_t>& page = page_[k / kMeshFilePage];
  if (page.empty()) {  // one page of the block table, verified against its hash
    const int64_t first = k / kMeshFilePage * kMeshFilePage;
    const int64_t n = std::min<int64_t>(kMeshFilePage, blocks_ - first);
    page.resize(static_cast<size_t>(n));
    const int64_t at = data_end_ + 8 * first;
    PreadAll(reinterpret_cast<char*>(page.data()), 8 * n, at);
    if (MeshFileBlockHash(reinterpret_cast<const char*>(page.data()), 8 * n) !=
        page_hash_[k / kMeshFilePage]) {
      page.clear();
      Fail(at, "page " + std::to_string(k / kMeshFilePage) +
                   " of the block table does not match its hash: the file is damaged");
    }
  }
  return page[k % kMeshFilePage];
}

MeshFile::~MeshFile() = default;
MeshFile::Fd::~Fd() {
  if (fd >= 0) ::close(fd);
}

void MeshFile::Fail(int64_t offset, const std::string& problem) const {
  throw InputError(path_, 0, "byte " + std::to_string(offset) + ": " + problem);
}

int64_t MeshFile::ElementBytes(Section s) const {
  static const int64_t kBytes[kSections] = {16, 1, 8, 4, 12};
  return kBytes[s];
}

int64_t MeshFile::Elements(Section s) const {
  switch (s) {
    case kXy:
    case kBoundary:
      return vertices_;
    case kV2tOff:
      return vertices_ + 1;
    case kV2t:
      return 3 * triangles_;
    case kTri:
      return triangles_;
    default:
      return 0;
  }
}

void MeshFile::ReadChecked(int64_t a, int64_t b, char* out) {
  if (a >= b) return;
  // Whole blocks, so each can be verified; read in pieces of at most 64 blocks.
  const int64_t first = (a - kMeshFileHeader) / kMeshFileBlock;
  const int64_t last = (b - 1 - kMeshFileHeader) / kMeshFileBlock;
  for (int64_t k0 = first; k0 <= last; k0 += 64) {
    const int64_t k1 = std::min(last + 1, k0 + 64);
    const int64_t lo = kMeshFileHeader + k0 * kMeshFileBlock;
    const int64_t hi = std::min(data_end_, kMeshFileHeader + k1 * kMeshFileBlock);
    scratch_.resize(static_cast<size_t>(hi - lo));
    PreadAll(scratch_.data(), hi - lo, lo);
    for (int64_t k = k0; k < k1; ++k) {
      if (verified_[k]) continue;
      const int64_t s = kMeshFileHeader + k * kMeshFileBlock - lo;
      const int64_t e = std::min(hi - lo, s + kMeshFileBlock);
      if (MeshFileBlockHash(scratch_.data() + s, static_cast<size_t>(e - s)) != BlockHash(k))
        Fail(lo + s, "block " + std::to_string(k) + " (bytes " + std::to_string(lo + s) + ".." +
                         std::to_string(lo + e - 1) +
                         ") does not match its hash: the file is damaged or was changed after "
                         "it was written");
      verified_[k] = true;
    }
    const int64_t from = std::max(a, lo), to = std::min(b, hi);
    std::memcpy(out + (from - a), scratch_.data() + (from - lo), static_cast<size_t>(to - from));
  }
}

void MeshFile::Read(Section s, int64_t first, int64_t count, void* out) {
  if (first < 0 || count < 0 || first > Elements(s) - count)
    throw std::logic_error("MeshFile::Read outside its section");
  const int64_t a = Offset(s) + first * ElementBytes(s);
  ReadChecked(a, a + count * ElementBytes(s), static_cast<char*>(out));
}

void MeshFile::ReadAt(Section s, const std::vector<int64_t>& at, void* out) {
  ReadSpans(
      s, at.size(), [&at](size_t i) { return std::make_pair(at[i], at[i] + 1); },
      static_cast<char*>(out));
}

void MeshFile::ReadRuns(Section s, const std::vector<int64_t>& first,
                        const std::vector<int64_t>& end, void* out) {
  if (first.size() != end.size()) throw std::logic_error("MeshFile::ReadRuns: unpaired runs");
  ReadSpans(
      s, first.size(), [&](size_t i) { return std::make_pair(first[i], end[i]); },
      static_cast<char*>(out));
}

void MeshFile::ReadSpans(Section s, size_t count,
                         const std::function<std::pair<int64_t, int64_t>(size_t)>& span, char* o) {
  const int64_t eb = ElementBytes(s);
  auto block_of = [](int64_t byte) { return (byte - kMeshFileHeader) / kMeshFileBlock; };
  constexpr int64_t kRunBlocks = 4096;  // 16 MiB
  std::vector<char> run;
  int64_t prev = 0;
  auto checked = [&](size_t j) {
    const auto [a, b] = span(j);
    if (a < 0 || b < a || b > Elements(s) || (j && a < prev))
      throw std::logic_error("MeshFile::ReadSpans: spans out of range or not increasing");
    prev = a;
    return std::make_pair(a, b);
  };
  // Spans whose blocks touch or adjoin are one read of whole blocks, so no block is read twice
  // however the elements straddle them (but where a 16 MiB run ends); a span of 16 MiB or more is
  // read straight into its place.
  for (size_t i = 0; i < count;) {
    const auto [a0, b0] = checked(i);
    if ((b0 - a0) * eb >= kRunBlocks * kMeshFileBlock) {
      Read(s, a0, b0 - a0, o);
      o += (b0 - a0) * eb;
      ++i;
      continue;
    }
    const int64_t first_block = block_of(Offset(s) + a0 * eb);
    int64_t last = first_block - 1;
    size_t j = i;
    for (; j < count; ++j) {
      const auto [a, b] = j == i ? std::make_pair(a0, b0) : checked(j);
      if (b == a) continue;
      const int64_t fa = Offset(s) + a * eb;
      if (j > i &&
          (block_of(fa) > last + 1 || block_of(Offset(s) + b * eb - 1) - first_block >= kRunBlocks))
        break;
      last = std::max(last, block_of(Offset(s) + b * eb - 1));
    }
    if (last >= first_block) {
      const int64_t lo = kMeshFileHeader + first_block * kMeshFileBlock;
      const int64_t hi = std::min(data_end_, kMeshFileHeader + (last + 1) * kMeshFileBlock);
      run.resize(static_cast<size_t>(hi - lo));
      ReadChecked(lo, hi, run.data());
      for (size_t k = i; k < j; ++k) {
        const auto [a, b] = span(k);
        if (b > a)
          std::memcpy(o, run.data() + (Offset(s) + a * eb - lo), static_cast<size_t>((b - a) * eb));
        o += (b - a) * eb;
      }
    }
    i = std::max(j, i + 1);
  }
}

void CheckMeshFileTopology(const std::string& path, const Mesh& m) {
  MeshFile f(path);
  const int64_t v = f.vertices(), t = f.triangles();
  if (m.NumVertices() != v)  // BuildMesh dropped vertices no triangle uses
    throw InputError(path, 0,
                     std::to_string(v - m.NumVertices()) +
                         " vertices lie in no triangle (a mesh file holds none)");
  std::vector<uint8_t> flag(static_cast<size_t>(v));
  f.Read(MeshFile::kBoundary, 0, v, flag.data());
  for (int64_t i = 0; i < v; ++i)
    if (flag[i] != m.boundary[i])
      throw InputError(path, 0,
                       "vertex " + std::to_string(i) + ": boundary flag " +
                           std::to_string(flag[i]) + ", but its triangles make it " +
                           (m.boundary[i] ? "a boundary" : "an interior") + " vertex");
  // Rows compared in pieces, so the check costs no second copy of the adjacency.
  constexpr int64_t kPiece = 1 << 20;
  std::vector<int64_t> off;
  for (int64_t a = 0; a <= v; a += kPiece) {
    const int64_t n = std::min(kPiece, v + 1 - a);
    off.resize(static_cast<size_t>(n));
    f.Read(MeshFile::kV2tOff, a, n, off.data());
    for (int64_t i = 0; i < n; ++i)
      if (off[i] != m.v2t.off[a + i])
        throw InputError(path, 0,
                         "v2t row offset " + std::to_string(a + i) + " is " +
                             std::to_string(off[i]) + ", the triangles make it " +
                             std::to_string(m.v2t.off[a + i]));
  }
  std::vector<int32_t> idx;
  for (int64_t a = 0; a < 3 * t; a += kPiece) {
    const int64_t n = std::min(kPiece, 3 * t - a);
    idx.resize(static_cast<size_t>(n));
    f.Read(MeshFile::kV2t, a, n, idx.data());
    for (int64_t i = 0; i < n; ++i)
      if (idx[i] != m.v2t.idx[a + i]) {
        const int64_t vert =
            std::upper_bound(m.v2t.off.begin(), m.v2t.off.end(), a + i) - m.v2t.off.begin() - 1;
        throw InputError(path, 0,
                         "vertex " + std::to_string(vert) + ": its v2t row lists triangle " +
                             std::to_string(idx[i]) + " where the triangles give " +
                             std::to_string(m.v2t.idx[a + i]));
      }
  }
}

RawMesh ReadMeshFileRaw(const std::string& path) {
  MeshFile f(path);
  RawMesh raw;
  raw.vertex_file = raw.triangle_file = path;
  raw.xy.resize(2 * static_cast<size_t>(f.vertices()));
  raw.tri.resize(3 * static_cast<size_t>(f.triangles()));
  f.Read(MeshFile::kXy, 0, f.vertices(), raw.xy.data());
  f.Read(MeshFile::kTri, 0, f.triangles(), raw.tri.data());
  // Corners checked here, so BuildMesh's messages can name a triangle rather than a line.
  for (size_t k = 0; k < raw.tri.size(); ++k)
    if (raw.tri[k] < 0 || raw.tri[k] >= f.vertices())
      throw InputError(path, 0,
                       "triangle " + std::to_string(k / 3) + ": corner " +
                           std::to_string(raw.tri[k]) + " outside 0.." +
                           std::to_string(f.vertices() - 1));
  return raw;
}

}  // namespace meshreuse
