// Format dispatch, VTK output and atomic writes; see mesh_io.h.
#include "core/mesh_io.h"

#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/mesh_file.h"
#include "core/progress.h"
#include "core/quality.h"
#include "core/vtu_io.h"

namespace meshreuse {

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool FileExists(const std::string& p) { return ::access(p.c_str(), F_OK) == 0; }

RawMesh ReadRawMesh(const std::string& path) {
  if (EndsWith(path, ".msh")) return ReadGmsh(path);
  if (EndsWith(path, ".mrm")) return ReadMeshFileRaw(path);
  if (EndsWith(path, ".node"))
    return ReadTriangleFiles(path, path.substr(0, path.size() - 5) + ".ele");
  if (EndsWith(path, ".ele"))
    return ReadTriangleFiles(path.substr(0, path.size() - 4) + ".node", path);
  if (FileExists(path + ".node") || FileExists(path + ".ele"))
    return ReadTriangleFiles(path + ".node", path + ".ele");
  if (!FileExists(path)) throw InputError(path, 0, "cannot open: No such file or directory");
  throw InputError(path, 0,
                   "cannot tell the mesh format: expected FILE.msh, FILE.node, FILE.ele or a "
                   "prefix P with P.node and P.ele");
}

Mesh ReadMesh(const std::string& path, std::vector<std::string>* warnings) {
  BuildReport report;
  Mesh m = BuildMesh(ReadRawMesh(path), &report);
  if (IsMeshFilePath(path)) CheckMeshFileTopology(path, m);
  if (warnings)
    for (std::string& w : report.warnings) warnings->push_back(std::move(w));
  return m;
}

void WriteVtk(const Mesh& m, const std::string& path, const std::vector<VtkField>& fields) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  const std::vector<double> vq = VertexQualities(m);
  const std::vector<double> tq = TriangleQualities(m);
  WriteAtomically(path, [&](std::FILE* f) {
    std::fprintf(f,
                 "# vtk DataFile Version 3.0\nmeshreuse mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n");
    std::fprintf(f, "POINTS %d double\n", nv);
    const uint64_t total = static_cast<uint64_t>(nv) + static_cast<uint64_t>(nt);
    for (int32_t v = 0; v < nv; ++v) {
      std::fprintf(f, "%.17g %.17g 0\n", m.xy[2 * int64_t{v}], m.xy[2 * int64_t{v} + 1]);
      if ((v & 0xffff) == 0) ReportProgress(static_cast<uint64_t>(v), total);
    }
    std::fprintf(f, "CELLS %d %lld\n", nt, 4LL * nt);
    for (int32_t t = 0; t < nt; ++t) {
      std::fprintf(f, "3 %d %d %d\n", m.tri[3 * int64_t{t}], m.tri[3 * int64_t{t} + 1],
                   m.tri[3 * int64_t{t} + 2]);
      if ((t & 0xffff) == 0) ReportProgress(static_cast<uint64_t>(nv) + t, total);
    }
    std::fprintf(f, "CELL_TYPES %d\n", nt);
    for (int32_t t = 0; t < nt; ++t) std::fputs("5\n", f);
    std::fprintf(f, "CELL_DATA %d\nSCALARS triangle_quality double 1\nLOOKUP_TABLE default\n", nt);
    for (int32_t t = 0; t < nt; ++t) std::fprintf(f, "%.9g\n", tq[t]);
    std::fprintf(f, "POINT_DATA %d\nSCALARS vertex_quality double 1\nLOOKUP_TABLE default\n", nv);
    for (int32_t v = 0; v < nv; ++v) std::fprintf(f, "%.9g\n", vq[v]);
    std::fprintf(f, "SCALARS boundary int 1\nLOOKUP_TABLE default\n");
    for (int32_t v = 0; v < nv; ++v) std::fprintf(f, "%d\n", int{m.boundary[v]});
    for (const VtkField& field : fields) {
      if (field.values.size() != static_cast<size_t>(nv))
        throw std::logic_error("VTK field " + field.name + " has the wrong length");
      std::fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", field.name.c_str());
      for (double x : field.values) std::fprintf(f, "%.9g\n", x);
    }
  });
}

void WriteVtu(const Mesh& m, const std::string& path, const std::vector<VtkField>& fields) {
  const int32_t nv = m.NumVertices(), nt = m.NumTriangles();
  // VertexQualities' sums (in the same order, so the same doubles) rounded once to Float32,
  // without its two double arrays (24 B a vertex at the peak).
  std::vector<float> vq(static_cast<size_t>(nv)), tq(static_cast<size_t>(nt));
#pragma omp parallel for schedule(static, 4096)
  for (int32_t t = 0; t < nt; ++t)
    tq[t] = static_cast<float>(TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{t}]));
#pragma omp parallel for schedule(static, 4096)
  for (int32_t v = 0; v < nv; ++v) {
    double sum = 0.0;
    for (const int32_t* p = m.v2t.RowBegin(v); p != m.v2t.RowEnd(v); ++p)
      sum += TriangleQuality(m.xy.data(), &m.tri[3 * int64_t{*p}]);
    const int64_t n = m.v2t.RowSize(v);
    vq[v] = n > 0 ? static_cast<float>(sum / static_cast<double>(n)) : 0.0f;
  }
  VtuGrid g;
  g.points = nv, g.xy = m.xy.data(), g.cells = nt, g.tri = m.tri.data();
  g.point_data.push_back(VtuArrayOf("vertex_quality", vq.data(), nv));
  g.point_data.push_back(VtuArrayOf("boundary", m.boundary.data(), nv));
  std::vector<std::vector<int32_t>> whole;
  for (const VtkField& field : fields) {
    if (field.values.size() != static_cast<size_t>(nv))
      throw std::logic_error("VTK field " + field.name + " has the wrong length");
    bool integral = true;
    for (double x : field.values)
      integral = integral && x == std::floor(x) && x >= INT32_MIN && x <= INT32_MAX;
    if (integral) {
      whole.emplace_back(field.values.begin(), field.values.end());
      g.point_data.push_back(VtuArrayOf(field.name, whole.back().data(), nv));
    } else {
      g.point_data.push_back(VtuArrayOf(field.name, field.values.data(), nv));
    }
  }
  g.cell_data.push_back(VtuArrayOf("triangle_quality", tq.data(), nt));
  WriteVtu(g, path);
}

void WritePermutation(const std::vector<int32_t>& new_to_old, const std::string& path,
                      const std::string& comment) {
  WriteAtomically(path, [&](std::FILE* f) {
    std::fprintf(f,
                 "# %s\n# one 0-based vertex id per line: line k is the old id of new vertex k\n",
                 comment.c_str());
    for (int32_t o : new_to_old) std::fprintf(f, "%d\n", o);
  });
}

bool IsPvtuPath(const std::string& target) { return EndsWith(target, ".pvtu"); }

std::string PvtuPiece(const std::string& target, int32_t rank) {
  return target.substr(0, target.size() - 5) + "_" + std::to_string(rank) + ".vtu";
}

std::vector<std::string> MeshOutputFiles(const std::string& target, int32_t pieces) {
  if (IsPvtuPath(target)) {
    if (pieces == 0)
      throw UsageError("-o '" + target +
                       "': a .pvtu (one .vtu piece per rank) is written by the distributed "
                       "smoother (meshreuse-mpi smooth, smooth-ranks); write one grid as .vtu");
    std::vector<std::string> out = {target};
    for (int32_t r = 0; r < pieces; ++r) out.push_back(PvtuPiece(target, r));
    return out;
  }
  for (const char* ext : {".vtk", ".vtu", ".msh", ".mrm"})
    if (EndsWith(target, ext)) return {target};
  const std::string prefix =
      EndsWith(target, ".node") ? target.substr(0, target.size() - 5) : target;
  // "" or "dir/" would write the hidden files ".node" and ".ele": a prefix must name a file.
  if (prefix.empty() || prefix.back() == '/')
    throw UsageError("-o '" + target + "': the prefix names no file (e.g. out/mesh)");
  return {prefix + ".node", prefix + ".ele"};
}

std::vector<std::string> InputFiles(const std::vector<std::string>& inputs) {
  std::vector<std::string> out;
  for (const std::string& p : inputs) {
    std::string prefix;
    if (EndsWith(p, ".node"))
      prefix = p.substr(0, p.size() - 5);
    else if (EndsWith(p, ".ele"))
      prefix = p.substr(0, p.size() - 4);
    else if (!EndsWith(p, ".msh") && !EndsWith(p, ".mrm") &&
             (FileExists(p + ".node") || FileExists(p + ".ele")))
      prefix = p;
    if (prefix.empty()) {
      out.push_back(p);
    } else {
      out.push_back(prefix + ".node");
      out.push_back(prefix + ".ele");
    }
  }
  return out;
}

std::vector<std::string> WriteMesh(const Mesh& m, const std::string& target,
                                   const std::vector<VtkField>& fields) {
  if (EndsWith(target, ".vtk")) {
    WriteVtk(m, target, fields);
    return {target};
  }
  if (EndsWith(target, ".vtu")) {
    WriteVtu(m, target, fields);
    return {target};
  }
  if (EndsWith(target, ".msh")) {
    WriteGmsh(m, target);
    return {target};
  }
  if (IsPvtuPath(target)) MeshOutputFiles(target);  // refused
  if (EndsWith(target, ".mrm")) {
    WriteMeshFile(m, target);
    return {target};
  }
  std::string prefix = target;
  if (EndsWith(prefix, ".node")) prefix.resize(prefix.size() - 5);
  WriteTriangleFiles(m, prefix);
  return {prefix + ".node", prefix + ".ele"};
}

}  // namespace meshreuse
