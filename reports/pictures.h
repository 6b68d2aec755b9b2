// What the report draws of the meshes themselves (C++ writes the data, scripts/plot_*.py draw):
//   - the paper's Figure 7, the meshes: each mesh's boundary edges and a sample of its vertices;
//   - smoothing before and after: a window of triangles around the mesh's centre, in the file's
//     coordinates and after smoothing to convergence;
//   - each ordering as a picture: a sample of vertices with their position in the ordering
//     (0 first, 1 last), so BFS's wavefront, RDR's chains and a curve's blocks can be seen.
// Samples keep the data small at any mesh size (every k-th vertex by id, deterministic).
#pragma once

#include <string>

#include "core/mesh.h"
#include "core/permutation.h"
#include "core/smoother.h"
#include "core/table.h"

namespace meshreuse {

// mesh, kind (edge: a boundary edge x1,y1 -> x2,y2; vertex: a sampled vertex at x1,y1)
Table MeshDrawingTable();
void AppendMeshDrawing(const std::string& name, const Mesh& m, Table* t, int max_vertices = 3000);

// mesh, stage (before|after), triangle, x1, y1, x2, y2, x3, y3: about `triangles` triangles
// nearest (by adjacency) the vertex closest to the bounding box's centre.
Table SmoothingWindowTable();
void AppendSmoothingWindow(const std::string& name, const Mesh& m, const SmoothOptions& smooth,
                           Table* t, int triangles = 400);

// mesh, ordering, x, y, position (rank / (V - 1)) for a sample of the vertices.
Table OrderPositionsTable();
void AppendOrderPositions(const std::string& name, const std::string& ordering, const Mesh& m,
                          const Permutation& p, Table* t, int max_vertices = 30000);

}  // namespace meshreuse
