// Weingarten options: guided projection's defaults, the checks and the presets of 003 Table 1.
#include "gproj/problems/weingarten/weingarten_options.h"

#include <cmath>

#include "gproj/common/input_error.h"

namespace gproj::weingarten {

SolverOptions WeingartenSolverDefaults() {
  SolverOptions s;
  s.max_iterations = 10;
  s.fairness_weight = 0.2;
  s.epsilon = 1e-3;
  s.residual_tolerance = 0.0;  // the alignment is minimised, not driven to zero
  s.step_tolerance = 1e-12;
  s.soft_weight_decay = 0.5;
  return s;
}

std::string WeingartenOptions::target_measure() const {
  return fixed_linear_relation && linear_relation_weight > 0.0 ? "max_relation_residual"
                                                               : "misalignment";
}

CurvatureRelation WeingartenOptions::relation() const {
  if (linear_relation_weight > 0.0) return CurvatureRelation::kLinear;
  if (bspline_relation_weight > 0.0) return CurvatureRelation::kBSpline;
  return CurvatureRelation::kNone;
}

bool WeingartenOptions::IsValid(std::string* why) const {
  const double weights[] = {
      alignment_weight,         bspline_relation_weight, linear_relation_weight,
      geodesic_parallel_weight, closeness_weight,        shape_weight,
      solver.fairness_weight,   definition_weight,       boundary_weight};
  for (double w : weights)
    if (!(w >= 0.0) || !std::isfinite(w)) {
      *why = "weights must be finite and ≥ 0";
      return false;
    }
  if (linear_relation_weight > 0.0 && bspline_relation_weight > 0.0) {
    *why = "choose one curvature relation: linear or B-spline, not both";
    return false;
  }
  if (!(solver.epsilon > 0.0)) {
    *why = "epsilon must be > 0";
    return false;
  }
  if (definition_weight <= 0.0) {
    *why = "the auxiliary definitions need a positive weight";
    return false;
  }
  if (samples_u < 0 || samples_v < 0 || samples_per_control < 1) {
    *why = "sample counts must be positive";
    return false;
  }
  if ((samples_u > 0 && samples_u < 5) || (samples_v > 0 && samples_v < 5)) {
    *why = "at least 5 samples per direction are needed (central differences of gradients)";
    return false;
  }
  if (!(soft_start >= 1.0) ||
      !(solver.soft_weight_decay > 0.0 && solver.soft_weight_decay <= 1.0)) {
    *why = "soft_start must be ≥ 1 and solver.soft_weight_decay in (0, 1]";
    return false;
  }
  if (!(tolerance >= 0.0)) {
    *why = "tolerance must be ≥ 0 (0: none)";
    return false;
  }
  if (refine_by_refit && !(refine_factor > 1.0 && refine_factor <= 4.0)) {
    *why = "refine_factor must be in (1, 4]";
    return false;
  }
  if (solver.max_iterations < 1 || refine_levels < 0) {
    *why = "max_iterations must be ≥ 1 and refine_levels ≥ 0";
    return false;
  }
  if (fixed_linear_relation && (!linear_coefficients.allFinite() ||
                                !(linear_coefficients.head<2>().cwiseAbs().maxCoeff() > 0.0))) {
    *why = "the linear relation needs finite coefficients with a or b non-zero";
    return false;
  }
  if (!curvature_auxiliaries &&
      (alignment_weight > 0.0 || bspline_relation_weight > 0.0 || geodesic_parallel_weight > 0.0 ||
       (linear_relation_weight > 0.0 && !(fixed_linear_relation && relation_on_surface)))) {
    *why =
        "without curvature auxiliaries only a fixed linear relation on the surface can be "
        "imposed (isoline alignment, geodesic parallel isolines, fitted and B-spline relations "
        "use the auxiliaries)";
    return false;
  }
  if (!(target_mean_curvature > 0.0)) {
    *why = "target_mean_curvature must be > 0";
    return false;
  }
  return true;
}

std::vector<std::string> WeingartenPresetNames() {
  return {"fig1", "fig2b", "fig2c", "fig2d", "fig3", "fig4b", "fig4c", "fig9b", "fig9c", "fig10"};
}

WeingartenOptions WeingartenPreset(const std::string& name) {
  WeingartenOptions o;  // fig1: ω_al 0.1, ω_cl 0.1 (also Figs. 7, 8, 12, 13)
  if (name == "fig1") return o;
  if (name == "fig2b") return o;
  if (name == "fig2c") {
    o.alignment_weight = 0.0;
    o.bspline_relation_weight = 10.0;
    return o;
  }
  if (name == "fig2d") {
    o.alignment_weight = 0.0;
    o.linear_relation_weight = 1.0;
    return o;
  }
  if (name == "fig3") {
    o.alignment_weight = 0.0;
    o.linear_relation_weight = 1.0;
    o.closeness_weight = 0.001;
    o.shape_weight = 0.001;
    o.boundary_weight = 10.0;
    o.soft_start = 30.0;  // the relation moves the surface far: short first steps
    o.solver.max_iterations = 30;
    // Far targets: keep only steps that lower the energy and reset the auxiliaries after each
    // step, so every step is a damped Gauss–Newton step on the surface's own H and K.
    o.solver.monotone = true;
    o.project_auxiliaries = true;
    // ε is only the floor of the adaptive damping here; at 1e-3 the nearly free tangential
    // motion of the control points makes the last digits converge very slowly.
    o.solver.epsilon = 1e-4;
    o.samples_per_control = kRelationSamplesPerControl;
    return o;
  }
  if (name == "fig4b" || name == "fig4c") {
    o.geodesic_parallel_weight = name == "fig4c" ? 0.2 : 0.0;
    o.closeness_weight = 0.001;
    o.shape_weight = 0.01;
    return o;
  }
  if (name == "fig9b" || name == "fig9c") {
    o.geodesic_parallel_weight = name == "fig9c" ? 0.05 : 0.0;
    return o;
  }
  if (name == "fig10") {
    o.geodesic_parallel_weight = 0.01;
    o.closeness_weight = 0.05;
    o.shape_weight = 0.001;
    return o;
  }
  std::string known;
  for (const auto& n : WeingartenPresetNames()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown preset '" + name + "' (known: " + known + ")");
}

}  // namespace gproj::weingarten
