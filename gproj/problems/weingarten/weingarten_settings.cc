// A Weingarten preset with the user's overrides.
#include "gproj/problems/weingarten/weingarten_settings.h"

#include "gproj/common/input_error.h"

namespace gproj::weingarten {
namespace {

// The relation asked by name, and a fixed linear relation over it.
void ApplyRelation(const WeingartenSettings& s, WeingartenOptions* o) {
  if (!s.relation.empty()) {
    if (s.relation != "none" && s.relation != "linear" && s.relation != "bspline")
      throw InputError("`relation` must be none, linear or bspline, not '" + s.relation + "'");
    o->linear_relation_weight = s.relation == "linear" ? 1.0 : 0.0;
    o->bspline_relation_weight = s.relation == "bspline" ? 10.0 : 0.0;
  }
  if (!s.linear.empty()) {
    if (s.linear.size() != 3)
      throw InputError("`linear` needs three coefficients a,b,c, got " +
                       std::to_string(s.linear.size()));
    o->fixed_linear_relation = true;
    o->linear_coefficients = Eigen::Vector3d(s.linear.data());
    o->samples_per_control = kRelationSamplesPerControl;
    if (o->linear_relation_weight == 0.0) o->linear_relation_weight = 1.0;
    o->bspline_relation_weight = 0.0;
  }
  if (!s.relation_on.empty() && !o->fixed_linear_relation)
    throw InputError(
        "`relation_on` places a fixed relation (`linear`, or a preset with one); preset " +
        s.preset + " with these options has none");
  if (!s.relation_on.empty()) o->relation_on_surface = s.relation_on == "surface";
}

template <typename T>
void Override(const std::optional<T>& value, T* field) {
  if (value) *field = *value;
}

}  // namespace

WeingartenOptions WeingartenSettings::ToOptions() const {
  WeingartenOptions o = WeingartenPreset(preset);
  ApplyRelation(*this, &o);
  if (!samples.empty()) {
    if (samples.size() != 2)
      throw InputError("`samples` needs two numbers NU NV, got " + std::to_string(samples.size()));
    o.samples_u = samples[0];
    o.samples_v = samples[1];
  }
  Override(max_iterations, &o.solver.max_iterations);
  Override(alignment, &o.alignment_weight);
  Override(closeness, &o.closeness_weight);
  Override(shape, &o.shape_weight);
  Override(geodesic_parallel, &o.geodesic_parallel_weight);
  Override(boundary, &o.boundary_weight);
  Override(epsilon, &o.solver.epsilon);
  Override(fairness, &o.solver.fairness_weight);
  Override(definitions, &o.definition_weight);
  Override(soft_start, &o.soft_start);
  // A tolerance of 0 would read as "none" (run the preset's iterations) and claim success.
  if (tolerance && !(*tolerance > 0.0))
    throw InputError("`tolerance` must be > 0 (leave it out to run the preset's iterations)");
  Override(tolerance, &o.tolerance);
  if (!steps.empty()) {
    o.solver.monotone = steps != "plain";
    o.project_auxiliaries = steps == "projected";
  }
  if (no_auxiliaries) o.curvature_auxiliaries = false;
  if (allow_folds) o.prevent_folds = false;
  o.refine_levels = refine_levels;
  if (refine_method != "insert" && refine_method != "refit")
    throw InputError("`refine_method` must be insert or refit (got '" + refine_method + "')");
  o.refine_by_refit = refine_method == "refit";
  std::string why;
  if (!o.IsValid(&why)) throw InputError(why);
  if (molds < 0) throw InputError("`molds` must be ≥ 0");
  return o;
}

}  // namespace gproj::weingarten
