// Reading and writing meshes. Readers return a RawMesh (BuildMesh validates the topology); every
// problem is an InputError naming the file and line. Writers go through core/output_file.h (a
// temporary renamed when complete; devices and FIFOs written in place; .node and .ele as a unit).
// Formats: Triangle .node/.ele (Shewchuk; any attribute and marker columns, numbering from 0 or 1,
// linear or quadratic triangles), Gmsh .msh 2.2 and 4.1 ASCII and 4.1 binary (triangles; other
// element types are skipped and counted), the distributed mesh file .mrm (mesh_file.h), VTK legacy
// ASCII (write only, for ParaView).
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
// -o target: PATH.vtk writes VTK, PATH.mrm the distributed mesh file (as stored: lay it out in
// Hilbert order first, LayOutForRanks); anything else is a prefix for .node/.ele. Returns files
// written.
std::vector<std::string> WriteMesh(const Mesh& m, const std::string& target);
// The files WriteMesh(target) writes, and the files a path names as input (a mesh's .node and
// .ele for FILE.node, FILE.ele or a prefix; the path itself otherwise): what an output must be
// checked against (an output through a link to an input's .node must not replace it).
std::vector<std::string> MeshOutputFiles(const std::string& target);
std::vector<std::string> InputFiles(const std::vector<std::string>& inputs);

// Writes a permutation in the file: ordering's format (one 0-based old id per line, new order),
// after a '#' comment line.
void WritePermutation(const std::vector<int32_t>& new_to_old, const std::string& path,
                      const std::string& comment);

}  // namespace meshreuse
