// VTK XML .vtu and .pvtu writers; see vtu_io.h.
#include "core/vtu_io.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#ifdef MESHREUSE_HAVE_ZLIB
#include <zlib.h>
#endif

#include "core/error.h"
#include "core/output_file.h"
#include "core/progress.h"

namespace meshreuse {

namespace {

constexpr int64_t kBlockBytes = int64_t{1} << 20;

size_t TypeBytes(VtuType t) {
  switch (t) {
    case VtuType::kUInt8:
      return 1;
    case VtuType::kInt32:
    case VtuType::kFloat32:
      return 4;
    case VtuType::kInt64:
    case VtuType::kFloat64:
      return 8;
  }
  return 8;
}

const char* TypeName(VtuType t) {
  switch (t) {
    case VtuType::kUInt8:
      return "UInt8";
    case VtuType::kInt32:
      return "Int32";
    case VtuType::kInt64:
      return "Int64";
    case VtuType::kFloat32:
      return "Float32";
    case VtuType::kFloat64:
      return "Float64";
  }
  return "Float64";
}

template <class T>
constexpr VtuType TypeOf();
template <>
constexpr VtuType TypeOf<uint8_t>() {
  return VtuType::kUInt8;
}
template <>
constexpr VtuType TypeOf<int32_t>() {
  return VtuType::kInt32;
}
template <>
constexpr VtuType TypeOf<int64_t>() {
  return VtuType::kInt64;
}
template <>
constexpr VtuType TypeOf<float>() {
  return VtuType::kFloat32;
}
template <>
constexpr VtuType TypeOf<double>() {
  return VtuType::kFloat64;
}

std::string Escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

// How an array is cut: whole tuples, about 1 MiB a block.
struct Blocks {
  int64_t tuple_bytes = 0, per_block = 0, count = 0, tuples = 0;
  explicit Blocks(const VtuArray& a)
      : tuple_bytes(static_cast<int64_t>(TypeBytes(a.type)) * a.components),
        per_block(std::max<int64_t>(1, kBlockBytes / tuple_bytes)),
        count((a.tuples + per_block - 1) / per_block),
        tuples(a.tuples) {}
  uint64_t Raw() const {
    return static_cast<uint64_t>(tuples) * static_cast<uint64_t>(tuple_bytes);
  }
  int64_t Tuples(int64_t b) const { return std::min(per_block, tuples - b * per_block); }
  // VTK's compressed header: blocks, a block's bytes, the last block's bytes when it is partial
  // (0 when full), each block's compressed size.
  std::vector<uint64_t> Header(const std::vector<uint64_t>& sizes) const {
    std::vector<uint64_t> h = {static_cast<uint64_t>(count),
                               static_cast<uint64_t>(per_block * tuple_bytes),
                               static_cast<uint64_t>((tuples % per_block) * tuple_bytes)};
    h.insert(h.end(), sizes.begin(), sizes.end());
    return h;
  }
};

struct Done {
  std::atomic<uint64_t> bytes{0};
  uint64_t total = 0;
};

// Blocks [b, e) of `a`, compressed in parallel into out[0, e - b).
void Compress(const VtuArray& a, const Blocks& k, int64_t b, int64_t e,
              std::vector<std::string>* out, Done* done) {
  out->assign(static_cast<size_t>(e - b), std::string());
#ifdef MESHREUSE_HAVE_ZLIB
  std::atomic<bool> failed{false};
#pragma omp parallel
  {
    std::vector<unsigned char> buf(static_cast<size_t>(k.per_block * k.tuple_bytes));
#pragma omp for schedule(dynamic)
    for (int64_t i = b; i < e; ++i) {
      const int64_t count = k.Tuples(i);
      const uLong n = static_cast<uLong>(count * k.tuple_bytes);
      a.fill(i * k.per_block, count, buf.data());
      uLongf size = compressBound(n);
      std::string& z = (*out)[static_cast<size_t>(i - b)];
      z.resize(size);
      if (compress2(reinterpret_cast<Bytef*>(&z[0]), &size, buf.data(), n, 1) != Z_OK)
        failed = true;
      z.resize(size);
      ReportProgress(done->bytes += n, done->total);  // the calling thread's listener only
    }
  }
  if (failed) throw EnvironmentError("zlib", "could not compress a .vtu array (out of memory?)");
#else
  (void)a, (void)k, (void)done;
#endif
}

void Put(std::FILE* f, const std::vector<uint64_t>& words) {
  std::fwrite(words.data(), 8, words.size(), f);
}

// An array, compressed, at f's position, f seekable: room for the header, the blocks compressed
// a batch at a time (memory: a few blocks a thread), then the header written into its room.
// Returns the bytes written.
uint64_t StreamCompressed(const VtuArray& a, std::FILE* f, Done* done) {
  const Blocks k(a);
  const off_t at = ftello(f);
  Put(f, std::vector<uint64_t>(3 + static_cast<size_t>(k.count), 0));
  std::vector<uint64_t> sizes;
  std::vector<std::string> batch;
  const int64_t step = 8 * std::max(1, omp_get_max_threads());
  uint64_t bytes = 8 * (3 + static_cast<uint64_t>(k.count));
  for (int64_t b = 0; b < k.count; b += step) {
    Compress(a, k, b, std::min(k.count, b + step), &batch, done);
    for (const std::string& z : batch) {
      std::fwrite(z.data(), 1, z.size(), f);
      sizes.push_back(z.size());
      bytes += z.size();
    }
  }
  const off_t end = ftello(f);
  if (at < 0 || end < 0 || fseeko(f, at, SEEK_SET) != 0) throw std::logic_error("vtu: seek");
  Put(f, k.Header(sizes));
  if (fseeko(f, end, SEEK_SET) != 0) throw std::logic_error("vtu: seek");
  return bytes;
}

// An array held whole in memory (an output that cannot seek, such as a pipe), compressed.
struct Held {
  std::vector<uint64_t> header;
  std::vector<std::string> blocks;
  uint64_t Bytes() const {
    uint64_t n = 8 * header.size();
    for (const std::string& z : blocks) n += z.size();
    return n;
  }
};

Held Hold(const VtuArray& a, Done* done) {
  const Blocks k(a);
  Held h;
  Compress(a, k, 0, k.count, &h.blocks, done);
  std::vector<uint64_t> sizes;
  for (const std::string& z : h.blocks) sizes.push_back(z.size());
  h.header = k.Header(sizes);
  return h;
}

// An array uncompressed: its byte count, then its tuples.
void StreamRaw(const VtuArray& a, std::FILE* f, Done* done) {
  const Blocks k(a);
  Put(f, {k.Raw()});
  std::vector<unsigned char> buf(static_cast<size_t>(k.per_block * k.tuple_bytes));
  for (int64_t b = 0; b < k.count; ++b) {
    const int64_t count = k.Tuples(b);
    a.fill(b * k.per_block, count, buf.data());
    std::fwrite(buf.data(), 1, static_cast<size_t>(count * k.tuple_bytes), f);
    ReportProgress(done->bytes += static_cast<uint64_t>(count * k.tuple_bytes), done->total);
  }
}

void DataArrayTag(std::string* x, const VtuArray& a, uint64_t offset) {
  *x += "        <DataArray type=\"" + std::string(TypeName(a.type)) + "\" Name=\"" +
        Escape(a.name) + "\"";
  if (a.components != 1) *x += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
  *x += " format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
}

std::string DataOpen(const char* tag, const VtuGrid& g, bool points) {
  std::string x = std::string("      <") + tag;
  if (points && !g.global_ids.empty()) x += " GlobalIds=\"" + Escape(g.global_ids) + "\"";
  return x + ">\n";
}

}  // namespace

template <class T>
VtuArray VtuArrayOf(std::string name, const T* data, int64_t tuples, int components) {
  VtuArray a;
  a.name = std::move(name);
  a.type = TypeOf<T>();
  a.components = components;
  a.tuples = tuples;
  a.fill = [data, components](int64_t first, int64_t count, void* out) {
    std::copy(data + first * components, data + (first + count) * components, static_cast<T*>(out));
  };
  return a;
}
template VtuArray VtuArrayOf(std::string, const uint8_t*, int64_t, int);
template VtuArray VtuArrayOf(std::string, const int32_t*, int64_t, int);
template VtuArray VtuArrayOf(std::string, const int64_t*, int64_t, int);
template VtuArray VtuArrayOf(std::string, const float*, int64_t, int);
template VtuArray VtuArrayOf(std::string, const double*, int64_t, int);

bool VtuCompressed() {
#ifdef MESHREUSE_HAVE_ZLIB
  return true;
#else
  return false;
#endif
}

void WriteVtu(const VtuGrid& g, const std::string& path) {
  for (const VtuArray& a : g.point_data)
    if (a.tuples != g.points) throw std::invalid_argument("vtu point array " + a.name + " length");
  for (const VtuArray& a : g.cell_data)
    if (a.tuples != g.cells) throw std::invalid_argument("vtu cell array " + a.name + " length");
  VtuArray points;
  points.name = "Points";
  points.components = 3;
  points.tuples = g.points;
  points.fill = [xy = g.xy](int64_t first, int64_t count, void* out) {
    double* o = static_cast<double*>(out);
    for (int64_t i = 0; i < count; ++i) {
      o[3 * i] = xy[2 * (first + i)];
      o[3 * i + 1] = xy[2 * (first + i) + 1];
      o[3 * i + 2] = 0.0;
    }
  };
  VtuArray connectivity = VtuArrayOf("connectivity", g.tri, 3 * g.cells);
  VtuArray offsets;
  offsets.name = "offsets";
  offsets.tuples = g.cells;
  if (3 * g.cells <= INT32_MAX) {
    offsets.type = VtuType::kInt32;
    offsets.fill = [](int64_t first, int64_t count, void* out) {
      for (int64_t i = 0; i < count; ++i)
        static_cast<int32_t*>(out)[i] = static_cast<int32_t>(3 * (first + i + 1));
    };
  } else {
    offsets.type = VtuType::kInt64;
    offsets.fill = [](int64_t first, int64_t count, void* out) {
      for (int64_t i = 0; i < count; ++i) static_cast<int64_t*>(out)[i] = 3 * (first + i + 1);
    };
  }
  VtuArray types;
  types.name = "types";
  types.type = VtuType::kUInt8;
  types.tuples = g.cells;
  types.fill = [](int64_t, int64_t count, void* out) {
    std::fill_n(static_cast<uint8_t*>(out), count, uint8_t{5});  // VTK_TRIANGLE
  };

  std::vector<const VtuArray*> all;
  for (const VtuArray& a : g.point_data) all.push_back(&a);
  for (const VtuArray& a : g.cell_data) all.push_back(&a);
  for (const VtuArray* a : {&points, &connectivity, &offsets, &types}) all.push_back(a);
  Done done;
  for (const VtuArray* a : all) done.total += Blocks(*a).Raw();
  // The XML before the data; `size` > 0 pads it to that many bytes with spaces between
  // </UnstructuredGrid> and <AppendedData> (whitespace between elements, which every XML parser
  // skips), so that a header written before the data can be rewritten in place afterwards.
  auto header = [&](const std::vector<uint64_t>& offset, size_t size = 0) {
    std::string x = "<?xml version=\"1.0\"?>\n";
    x += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\"";
    if (VtuCompressed()) x += " compressor=\"vtkZLibDataCompressor\"";
    x += ">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" + std::to_string(g.points) +
         "\" NumberOfCells=\"" + std::to_string(g.cells) + "\">\n";
    size_t k = 0;
    x += DataOpen("PointData", g, true);
    for (size_t i = 0; i < g.point_data.size(); ++i, ++k) DataArrayTag(&x, *all[k], offset[k]);
    x += "      </PointData>\n" + DataOpen("CellData", g, false);
    for (size_t i = 0; i < g.cell_data.size(); ++i, ++k) DataArrayTag(&x, *all[k], offset[k]);
    x += "      </CellData>\n      <Points>\n";
    DataArrayTag(&x, *all[k], offset[k]), ++k;
    x += "      </Points>\n      <Cells>\n";
    for (int i = 0; i < 3; ++i, ++k) DataArrayTag(&x, *all[k], offset[k]);
    x += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
    const std::string appended = "  <AppendedData encoding=\"raw\">\n_";
    if (size > x.size() + appended.size()) x.append(size - x.size() - appended.size(), ' ');
    return x + appended;
  };
  const char* tail = "\n  </AppendedData>\n</VTKFile>\n";
  WriteAtomically(path, [&](std::FILE* f) {
    std::vector<uint64_t> offset(all.size(), 0);
    if (!VtuCompressed()) {  // sizes known up front
      for (size_t i = 1; i < all.size(); ++i)
        offset[i] = offset[i - 1] + 8 + Blocks(*all[i - 1]).Raw();
      const std::string x = header(offset);
      std::fwrite(x.data(), 1, x.size(), f);
      for (const VtuArray* a : all) StreamRaw(*a, f, &done);
    } else if (ftello(f) >= 0) {  // a regular file: the header rewritten once sizes are known
      // Room for the longest offsets (20 digits each).
      const std::string x = header(std::vector<uint64_t>(all.size(), UINT64_MAX));
      std::fwrite(x.data(), 1, x.size(), f);
      uint64_t at = 0;
      for (size_t i = 0; i < all.size(); ++i) {
        offset[i] = at;
        at += StreamCompressed(*all[i], f, &done);
      }
      std::fputs(tail, f);
      const std::string y = header(offset, x.size());
      if (y.size() != x.size() || fseeko(f, 0, SEEK_SET) != 0) throw std::logic_error("vtu: seek");
      std::fwrite(y.data(), 1, y.size(), f);
      if (fseeko(f, 0, SEEK_END) != 0) throw std::logic_error("vtu: seek");
      return;
    } else {  // a pipe or device: the compressed arrays held until the header can be written
      std::vector<Held> held;
      for (const VtuArray* a : all) held.push_back(Hold(*a, &done));
      for (size_t i = 1; i < all.size(); ++i) offset[i] = offset[i - 1] + held[i - 1].Bytes();
      const std::string x = header(offset);
      std::fwrite(x.data(), 1, x.size(), f);
      for (const Held& h : held) {
        Put(f, h.header);
        for (const std::string& z : h.blocks) std::fwrite(z.data(), 1, z.size(), f);
      }
    }
    std::fputs(tail, f);
  });
}

void WritePvtu(const std::string& path, const std::vector<std::string>& pieces,
               const VtuGrid& like) {
  auto decl = [](const VtuArray& a) {
    std::string d = "      <PDataArray type=\"" + std::string(TypeName(a.type)) + "\" Name=\"" +
                    Escape(a.name) + "\"";
    if (a.components != 1) d += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
    return d + "/>\n";
  };
  std::string x = "<?xml version=\"1.0\"?>\n";
  x += "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"1\">\n    <PPointData";
  if (!like.global_ids.empty()) x += " GlobalIds=\"" + Escape(like.global_ids) + "\"";
  x += ">\n";
  for (const VtuArray& a : like.point_data) x += decl(a);
  x += "    </PPointData>\n    <PCellData>\n";
  for (const VtuArray& a : like.cell_data) x += decl(a);
  x += "    </PCellData>\n    <PPoints>\n      <PDataArray type=\"Float64\" "
       "NumberOfComponents=\"3\"/>\n    </PPoints>\n";
  for (const std::string& p : pieces) x += "    <Piece Source=\"" + Escape(p) + "\"/>\n";
  x += "  </PUnstructuredGrid>\n</VTKFile>\n";
  WriteTextFile(path, x);
}

}  // namespace meshreuse
