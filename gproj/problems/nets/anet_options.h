#pragma once
// The options of the A-net step, shared by `anet` and `hnet` (whose first stage it is): one name,
// doc, default and range for both.

#include <string>

#include "gproj/problems/mesh/mesh_options.h"
#include "gproj/problems/nets/anet.h"
#include "gproj/problems/run/shared_options.h"

namespace gproj::nets {

// solver, star_form, tolerance, tangent, point, fairness_order, the solver's options, the panel
// bounds and the vertex control. `star_form` receives "normals" or "quads" (StarFormOf).
template <typename S>
void AddANetOptions(OptionSchema<S>* s, std::function<ANetOptions&(S&)> anet,
                    std::function<SolverKind&(S&)> method,
                    std::function<std::string&(S&)> star_form) {
  AddMethodOption<S>(s, method);
  s->template Field<std::string>("star_form", OptionType::kChoice,
                                 "Vertex-star planarity: normals (auxiliary normal per inner "
                                 "vertex) or quads (n-2 quads of each star)",
                                 star_form)
      .Choices({"normals", "quads"});
  s->template Field<double>("tolerance", OptionType::kNumber,
                            "The A-net step stops when max star planarity (neighbour distance "
                            "from the star plane / mean edge) is <= this",
                            [anet](S& x) -> double& { return anet(x).tolerance; })
      .Positive();
  s->template Field<double>("tangent", OptionType::kNumber,
                            "Weight of the distance to the reference's tangent planes",
                            [anet](S& x) -> double& { return anet(x).tangent_weight; })
      .NonNegative();
  s->template Field<double>("point", OptionType::kNumber,
                            "Weight of the distance to the reference's closest points",
                            [anet](S& x) -> double& { return anet(x).point_weight; })
      .NonNegative();
  s->template Field<int>("fairness_order", OptionType::kInt,
                         "2: second differences, 3: third differences",
                         [anet](S& x) -> int& { return anet(x).fairness_order; })
      .Range(2, 3);
  AddSolverOptions<S>(s, [anet](S& x) -> SolverOptions& { return anet(x).solver; });
  AddPanelBoundsOptions<S>(s, [anet](S& x) -> PanelBoundsOptions& { return anet(x).panels; });
  AddVertexControlOptions<S>(s, [anet](S& x) -> VertexControlOptions& { return anet(x).vertices; });
}

inline StarPlanarityForm StarFormOf(const std::string& name) {
  return name == "quads" ? StarPlanarityForm::kQuads : StarPlanarityForm::kNormals;
}

// The shortfall of a net that missed its tolerance with the whole boundary held or gliding: why
// that is likely (the asymptotic lines' equations are hyperbolic, fixed by two crossing curves);
// empty otherwise.
inline std::string BoundaryControlNote(const VertexControlOptions& vertices) {
  if (!(vertices.fix_boundary || vertices.glide_boundary)) return "";
  return std::string(
             "note: an asymptotic net is fixed by two crossing boundary curves; keeping the whole "
             "boundary") +
         (vertices.glide_boundary ? " on the input's loops" : "") +
         " over-determines it unless the boundary is already asymptotic (hold a few vertices "
         "with `fixed` instead)";
}

}  // namespace gproj::nets
