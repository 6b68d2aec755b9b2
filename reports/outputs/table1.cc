// table1: the meshes (the paper's Table 1): vertices, triangles and interior vertices, the paper's
// counts for a mesh of its name, and our difference.
#include "reports/paper.h"
#include "reports/report_outputs.h"

namespace meshreuse {

ReportPart ReportTable1(const ReportData& d) {
  using namespace report;
  ReportPart p;
  p.table = Table({"label", "mesh", "vertices", "triangles", "interior", "paper_vertices",
                   "paper_triangles", "vertices_vs_paper_pct"});
  for (const ReportMesh& m : d.meshes) {
    const auto p1 = paper::Table1(m.name);
    p.table.AddRow({p1 ? p1->label : "", m.name, Int(m.vertices), Int(m.triangles), Int(m.interior),
                    p1 ? Int(p1->vertices) : "", p1 ? Int(p1->triangles) : "",
                    p1 ? Num(100.0 * (m.vertices - p1->vertices) / p1->vertices, 1) : ""});
  }
  p.note =
      "Our meshes are Triangle meshes of shipped shapes drawn after the paper's names, at its "
      "vertex counts (the paper's meshes are not public).";
  return p;
}

}  // namespace meshreuse
