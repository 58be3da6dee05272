#include "gproj/problems/circular/circular_mesh.h"

#include <cstdio>

#include "gproj/geometry/mesh/circle.h"
#include "gproj/problems/mesh/planarity_measures.h"

namespace gproj::circular {

NamedValues MeasureCircularMesh(const PolyMesh& mesh) {
  const PlanarityMeasures p = MeasurePlanarity(mesh, mesh);
  const CircularityMeasures c = MeasureCircularity(mesh);
  return {{"max_planarity", p.max_planarity},
          {"mean_planarity", p.mean_planarity},
          {"max_concyclicity", c.max_concyclicity},
          {"mean_concyclicity", c.mean_concyclicity},
          {"worst_concyclic_face", static_cast<double>(c.worst_face)},
          {"folded_quads", static_cast<double>(c.folded_quads)}};
}

std::string CrossedQuadsFault(const NamedValues& measures, const std::string& hint) {
  const double folded = ValueOf(measures, "folded_quads");
  if (!(folded > 0.0)) return "";
  return "the canal mesh has " + std::to_string(static_cast<long long>(folded)) +
         " crossed quads (" + hint + ")";
}

nlohmann::json MRevolutionJson(const MRevolutionChoice& choice, double t, int root) {
  nlohmann::json centres = nlohmann::json::array();
  for (const Eigen::Vector3d& c : choice.centres) centres.push_back({c.x(), c.y(), c.z()});
  return {{"t", t},
          {"centres", centres},
          {"root", root},
          {"image_side_angle", choice.image.side_angle},
          {"image_diagonals", choice.image.diagonals}};
}

std::string CircularMeasuresLine(const std::string& label, const NamedValues& measures) {
  char line[256];
  std::snprintf(line, sizeof(line),
                "%s: max planarity %.3e, max concyclicity %.3e (diagonal distance and distance to "
                "the fitted circle, per mean edge)",
                label.c_str(), ValueOf(measures, "max_planarity"),
                ValueOf(measures, "max_concyclicity"));
  return line;
}

}  // namespace gproj::circular
