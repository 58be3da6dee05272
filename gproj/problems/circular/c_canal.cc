#include "gproj/problems/circular/c_canal.h"

#include <ceres/ceres.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/circular/combescure.h"

namespace gproj::circular {

bool CCanalOptions::IsValid(std::string* why) const {
  if (segments < 1 || segments > 100000) {
    *why = "the cross-section needs 1 to 100000 segments";
    return false;
  }
  if (static_cast<int>(section_scales.size()) != segments) {
    *why = "the cross-section needs one scale per segment (" + std::to_string(segments) +
           "), got " + std::to_string(section_scales.size());
    return false;
  }
  for (double s : section_scales)
    if (!(s > 0.0) || !std::isfinite(s)) {
      *why = "the cross-section's scales must be finite and > 0";
      return false;
    }
  if (max_iterations < 0 || !(length_tolerance > 0.0)) {
    *why = "the iterations must be >= 0 and the length tolerance > 0";
    return false;
  }
  return true;
}

namespace {

// The canal surface of lengths ℓ and its Combescure transform; false when the construction
// refuses ℓ (a length past the circle's diameter, a folding quad).
bool Transform(const CircularStripInput& input, const std::vector<double>& lengths,
               const FrameAngles& angles, const CCanalOptions& options, PolyMesh* canal,
               PolyMesh* c_canal) {
  CircularStripInput with = input;
  with.lengths = lengths;
  try {
    *canal =
        MeshCanalSurface(MakeCyclidicStrip(BuildCircularStrip(with), angles), options.segments);
    const GridShape shape{static_cast<int>(input.curve.size()) - 1, options.segments};
    CombescureLengths l = ReferenceLengths(*canal, shape);
    for (int j = 0; j < options.segments; ++j) l.row[j] *= options.section_scales[j];
    l.origin = input.curve[0];
    *c_canal = CombescureByPropagation(*canal, shape, l);
  } catch (const InputError&) {
    return false;  // the line search then tries a shorter step
  }
  return true;
}

// L'_k = |P_k − Q'_k|: the C-canal's chord across row k.
std::vector<double> RowChords(const PolyMesh& mesh, int rows, int segments) {
  std::vector<double> out;
  for (int k = 0; k <= rows; ++k)
    out.push_back((mesh.point(mesh.vertex_handle(k * (segments + 1) + segments)) -
                   mesh.point(mesh.vertex_handle(k * (segments + 1))))
                      .norm());
  return out;
}

class LengthObjective final : public ceres::FirstOrderFunction {
 public:
  LengthObjective(const CircularStripInput& input, const FrameAngles& angles,
                  const CCanalOptions& options, double unit)
      : input_(input), angles_(angles), options_(options), unit_(unit) {}
  int NumParameters() const override { return static_cast<int>(input_.lengths.size()); }
  // The best point evaluated: a line search that fails near the construction's limits (a quad
  // about to fold) leaves Ceres' parameters at the start, not at the progress made.
  const std::vector<double>& best() const { return best_u_; }

  bool Evaluate(const double* u, double* cost, double* gradient) const override {
    if (!Energy(u, cost)) return false;
    if (*cost < best_cost_) best_cost_ = *cost, best_u_.assign(u, u + NumParameters());
    if (!gradient) return true;
    std::vector<double> x(u, u + NumParameters());
    for (int k = 0; k < NumParameters(); ++k) {
      const double h = 1e-6;
      double plus = 0.0, minus = 0.0;
      x[k] = u[k] + h;
      if (!Energy(x.data(), &plus)) return false;
      x[k] = u[k] - h;
      if (!Energy(x.data(), &minus)) return false;
      x[k] = u[k];
      gradient[k] = (plus - minus) / (2 * h);
    }
    return true;
  }

 private:
  bool Energy(const double* u, double* cost) const {
    std::vector<double> lengths(input_.lengths.size());
    for (size_t k = 0; k < lengths.size(); ++k) lengths[k] = input_.lengths[k] * std::exp(u[k]);
    PolyMesh canal, c_canal;
    if (!Transform(input_, lengths, angles_, options_, &canal, &c_canal)) return false;
    const std::vector<double> chords =
        RowChords(c_canal, static_cast<int>(input_.curve.size()) - 1, options_.segments);
    *cost = 0.0;
    for (size_t k = 0; k < chords.size(); ++k) {
      const double e = (chords[k] - input_.lengths[k]) / unit_;
      *cost += 0.5 * e * e;
    }
    return std::isfinite(*cost);
  }

  CircularStripInput input_;
  FrameAngles angles_;
  CCanalOptions options_;
  double unit_;
  mutable double best_cost_ = std::numeric_limits<double>::infinity();
  mutable std::vector<double> best_u_;
};

double MaxRelativeError(const std::vector<double>& chords, const std::vector<double>& targets,
                        double unit) {
  double worst = 0.0;
  for (size_t k = 0; k < chords.size(); ++k)
    worst = std::max(worst, std::abs(chords[k] - targets[k]) / unit);
  return worst;
}

}  // namespace

CCanalSurface BuildCCanalSurface(const CircularStripInput& input, const FrameAngles& angles,
                                 const CCanalOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (input.lengths.size() != input.curve.size())
    throw InputError("the C-canal needs one length per curve point");
  double unit = 0.0;
  for (double l : input.lengths) unit += l / input.lengths.size();
  CCanalSurface out;
  // The start (ℓ = L) through the construction itself, so that a refusal names its reason.
  MeshCanalSurface(MakeCyclidicStrip(BuildCircularStrip(input), angles), options.segments);
  const int rows = static_cast<int>(input.curve.size()) - 1;
  PolyMesh canal, c_canal;
  if (!Transform(input, input.lengths, angles, options, &canal, &c_canal))
    throw InputError("the canal surface of the given lengths cannot carry the cross-section");
  out.initial_length_error =
      MaxRelativeError(RowChords(c_canal, rows, options.segments), input.lengths, unit);
  std::vector<double> u(input.lengths.size(), 0.0);
  auto* objective = new LengthObjective(input, angles, options, unit);
  ceres::GradientProblem problem(objective);  // owns the objective
  ceres::GradientProblemSolver::Options ceres_options;
  ceres_options.line_search_direction_type = ceres::BFGS;
  ceres_options.max_num_iterations = options.max_iterations;
  ceres_options.function_tolerance = 1e-16;
  ceres_options.gradient_tolerance = 1e-16;
  ceres_options.parameter_tolerance = 1e-14;
  ceres_options.logging_type = ceres::SILENT;
  ceres::GradientProblemSolver::Summary summary;
  if (options.max_iterations > 0) ceres::Solve(ceres_options, problem, u.data(), &summary);
  out.iterations =
      static_cast<int>(summary.iterations.size() > 0 ? summary.iterations.size() - 1 : 0);
  out.message = summary.BriefReport();
  if (!summary.IsSolutionUsable() && !objective->best().empty()) u = objective->best();
  for (size_t k = 0; k < u.size(); ++k)
    out.canal_lengths.push_back(input.lengths[k] * std::exp(u[k]));
  if (!Transform(input, out.canal_lengths, angles, options, &out.canal, &out.mesh))
    throw InputError("the optimised canal surface cannot be built");
  out.lengths = RowChords(out.mesh, rows, options.segments);
  out.max_length_error = MaxRelativeError(out.lengths, input.lengths, unit);
  out.converged = out.max_length_error <= options.length_tolerance;
  return out;
}

}  // namespace gproj::circular
