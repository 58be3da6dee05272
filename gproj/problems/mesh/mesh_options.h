#pragma once
// The option groups of the mesh problems, one name, doc, range and rule everywhere: the panel
// bounds and the vertex control. Each takes the schema and a function from the problem's
// settings to the struct it fills; the defaults stay those of the problem's own Options.

#include <functional>

#include "gproj/problems/mesh/panel_bounds.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/run/option_schema.h"

namespace gproj {

// min_angle, edge_length, allow_folds.
template <typename S>
void AddPanelBoundsOptions(OptionSchema<S>* schema, std::function<PanelBoundsOptions&(S&)> panels) {
  schema
      ->template Field<double>(
          "min_angle", OptionType::kNumber,
          "Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already "
          "outside in the input is kept from getting worse); 0 only keeps quads convex",
          [panels](S& s) -> double& { return panels(s).min_angle_deg; })
      .Range(0.0, 59.9)
      .Unit("deg")
      .Group("panels");
  schema
      ->Custom("edge_length", OptionType::kNumbers,
               "Every edge length ends within these, to the tolerance (an edge outside in the "
               "input is brought in; the run converges only when all are); without it no edge "
               "shrinks below 10% of its input length",
               nullptr,
               [panels](const nlohmann::json& value, S* s) {
                 panels(*s).min_edge_length = value[0].get<double>();
                 panels(*s).max_edge_length = value[1].get<double>();
               })
      .NonNegative()
      .Count(2, "MIN,MAX")
      .Unit("input units")
      .Group("panels");
  schema
      ->Custom("allow_folds", OptionType::kBool,
               "No corner-angle or default edge bounds: quads may turn non-convex or fold", false,
               [panels](const nlohmann::json& value, S* s) {
                 if (value.get<bool>()) panels(*s).AllowFolds();
               })
      .Group("panels");
}

// fix_boundary, glide_boundary (held vertices are the problem's "fixed" input).
template <typename S>
void AddVertexControlOptions(OptionSchema<S>* schema,
                             std::function<VertexControlOptions&(S&)> vertices) {
  schema
      ->template Field<bool>("fix_boundary", OptionType::kBool,
                             "Every boundary vertex stays where it is",
                             [vertices](S& s) -> bool& { return vertices(s).fix_boundary; })
      .Group("vertices");
  schema
      ->template Field<bool>("glide_boundary", OptionType::kBool,
                             "Boundary vertices slide along the input's boundary (they stay on "
                             "it to rounding)",
                             [vertices](S& s) -> bool& { return vertices(s).glide_boundary; })
      .Group("vertices");
}

}  // namespace gproj
