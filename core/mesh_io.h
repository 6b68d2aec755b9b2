// Reading and writing meshes. Readers return a RawMesh (BuildMesh validates the topology); every
// problem is an InputError naming the file and line. Writers go through core/output_file.h (a
// temporary renamed when complete; devices and FIFOs written in place; .node and .ele as a unit).
// Formats: Triangle .node/.ele (Shewchuk; any attribute and marker columns, numbering from 0 or 1,
// linear or quadratic triangles), Gmsh .msh 2.2 and 4.1 ASCII and 4.1 binary (triangles; other
// element types are skipped and counted), the distributed mesh file .mrm (mesh_file.h); written
// only: VTK legacy ASCII (.vtk), VTK XML (.vtu, binary and compressed: vtu_io.h) and Gmsh 4.1
// ASCII (.msh).
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/output_file.h"

namespace meshreuse {

RawMesh ReadTriangleFiles(const std::string& node_path, const std::string& ele_path);
RawMesh ReadGmsh(const std::string& msh_path);
RawMesh ReadGmshBinary(const std::string& msh_path);  // 4.1 binary; ReadGmsh picks it itself

// Picks the reader from the path: FILE.msh; FILE.mrm (mesh_file.h); FILE.node or FILE.ele (the
// other one beside it); or a prefix P with P.node and P.ele.
RawMesh ReadRawMesh(const std::string& path);
bool FileExists(const std::string& path);  // whether `path` names anything (access F_OK)

// Read + BuildMesh. Reader and builder warnings (skipped elements, dropped vertices) go to
// `warnings` when given.
Mesh ReadMesh(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Writes PREFIX.node and PREFIX.ele (numbered from 1, with a boundary marker column).
void WriteTriangleFiles(const Mesh& m, const std::string& prefix);
// A per-vertex field for VTK (a name without spaces, one value per vertex).
struct VtkField {
  std::string name;
  std::vector<double> values;
};
// Writes a VTK legacy unstructured grid with vertex quality, boundary flag and triangle quality,
// and `fields` as further point data (ParaView shows each).
void WriteVtk(const Mesh& m, const std::string& path, const std::vector<VtkField>& fields = {});
// The same as a VTK XML grid (vtu_io.h): the qualities as Float32 (display fields: the legacy
// file prints 9 digits), the boundary flag as UInt8, a field of whole numbers that fit as Int32,
// any other as Float64.
void WriteVtu(const Mesh& m, const std::string& path, const std::vector<VtkField>& fields = {});
// Writes Gmsh 4.1 ASCII: one surface entity, nodes tagged 1..n in id order, 3-node triangles
// tagged 1..m; coordinates printed to round-trip (%.17g).
void WriteGmsh(const Mesh& m, const std::string& path);
// -o target: PATH.vtk writes legacy VTK, PATH.vtu VTK XML, PATH.msh Gmsh, PATH.mrm the distributed
// mesh file (as stored: lay it out in Hilbert order first, LayOutForRanks); anything else is a
// prefix for .node/.ele. PATH.pvtu is refused (UsageError): one piece per rank is the distributed
// smoother's (core/ranks/rank_piece.h). `fields` go to .vtk and .vtu. Returns files written.
std::vector<std::string> WriteMesh(const Mesh& m, const std::string& target,
                                   const std::vector<VtkField>& fields = {});
bool IsPvtuPath(const std::string& target);
// The files WriteMesh(target) writes, and the files a path names as input (a mesh's .node and
// .ele for FILE.node, FILE.ele or a prefix; the path itself otherwise): what an output must be
// checked against (an output through a link to an input's .node must not replace it). PATH.pvtu:
// with `pieces` ranks, the .pvtu and its pieces (PvtuPiece); with 0, a UsageError (one grid is a
// .vtu).
std::vector<std::string> MeshOutputFiles(const std::string& target, int32_t pieces = 0);
std::string PvtuPiece(const std::string& target, int32_t rank);  // PATH_RANK.vtu beside PATH.pvtu
std::vector<std::string> InputFiles(const std::vector<std::string>& inputs);

// Writes a permutation in the file: ordering's format (one 0-based old id per line, new order),
// after a '#' comment line.
void WritePermutation(const std::vector<int32_t>& new_to_old, const std::string& path,
                      const std::string& comment);

}  // namespace meshreuse
