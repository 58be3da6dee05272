#include "gproj/problems/weingarten/weingarten.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "gproj/common/input_error.h"
#include "gproj/constraints/closeness.h"
#include "gproj/constraints/control_net.h"
#include "gproj/constraints/curvature_relations.h"
#include "gproj/constraints/geodesic_parallel_isolines.h"
#include "gproj/constraints/isoline_alignment.h"
#include "gproj/constraints/polyline_fairness.h"

namespace gproj::weingarten {
namespace {

// Fold prevention: neighbouring normals on the check grid (kFoldGridFactor × the samples per
// direction, the grid RunWeingarten checks the result on) may turn by at most 60°.
constexpr double kFoldCosine = 0.5;

// Rows are multiplied by the weights of Table 1 (003 §3.3): a family's weight on φ² is ω².
double Squared(double w) { return w * w; }

// Derivatives (s_u, s_v, s_uu, s_uv, s_vv) of every sample for control points `c` (nC × 3).
std::vector<std::array<Eigen::Vector3d, 5>> SampleDerivatives(const SampleMaps& maps,
                                                              const Eigen::MatrixX3d& c) {
  std::array<Eigen::MatrixX3d, 5> d;
  for (int k = 0; k < 5; ++k) d[k] = maps.d[k + 1] * c;
  std::vector<std::array<Eigen::Vector3d, 5>> out(maps.num_samples());
  for (int s = 0; s < maps.num_samples(); ++s)
    for (int k = 0; k < 5; ++k) out[s][k] = d[k].row(s).transpose();
  return out;
}

double MeanAbsPrincipalCurvature(const std::vector<double>& h, const std::vector<double>& k) {
  double sum = 0.0;
  for (size_t i = 0; i < h.size(); ++i) {
    const double r = std::sqrt(std::max(0.0, h[i] * h[i] - k[i]));
    sum += std::abs(h[i] + r) + std::abs(h[i] - r);
  }
  return h.empty() ? 0.0 : sum / (2.0 * h.size());
}

double BoundingBoxDiagonal(const Eigen::MatrixX3d& points) {
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).stableNorm();
}

}  // namespace

int WeingartenVariableCount(int nu, int nv, int su, int sv, bool geodesic_parallel) {
  return 3 * nu * nv + (geodesic_parallel ? 20 : 12) * su * sv;
}

double SampleUnitCurvatures(const BSplineSurface& surface, const SampleMaps& maps,
                            std::vector<double>* h, std::vector<double>* k) {
  double unit = BoundingBoxDiagonal(surface.control);
  if (!(unit > 0.0) || !std::isfinite(unit)) unit = 1.0;
  const Eigen::MatrixX3d control = (surface.control.rowwise() - surface.control.row(0)) / unit;
  const auto d = SampleDerivatives(maps, control);
  h->resize(d.size());
  k->resize(d.size());
  for (size_t s = 0; s < d.size(); ++s) {
    const auto a = CurvatureAuxiliaries::ExactAuxiliary(d[s]);
    (*h)[s] = a[kH];
    (*k)[s] = a[kK];
  }
  return unit;
}

void SampleCurvatures(const BSplineSurface& surface, const SampleMaps& maps, std::vector<double>* h,
                      std::vector<double>* k) {
  const double unit = SampleUnitCurvatures(surface, maps, h, k);
  for (double& x : *h) x /= unit;
  for (double& x : *k) x = x / unit / unit;
}

WeingartenMeasures MeasureWeingarten(const BSplineSurface& surface, const BSplineSurface& reference,
                                     int su, int sv) {
  const SampleMaps maps = MakeSampleMaps(surface, su, sv);
  WeingartenMeasures m;
  // The misalignment is scale-free: measured at unit scale, where its products of gradients
  // neither overflow nor underflow; H and K are then brought to the surface's units.
  const double unit = SampleUnitCurvatures(surface, maps, &m.h, &m.k);
  m.mean_abs_principal_curvature = MeanAbsPrincipalCurvature(m.h, m.k) / unit;
  double num = 0.0, den = 0.0;
  for (int a = 1; a + 1 < su; ++a)
    for (int b = 1; b + 1 < sv; ++b) {
      const double cu = 1.0 / (maps.u[a + 1] - maps.u[a - 1]);
      const double cv = 1.0 / (maps.v[b + 1] - maps.v[b - 1]);
      auto gradient = [&](const std::vector<double>& psi) {
        return CentralGradient(psi[maps.Index(a + 1, b)], psi[maps.Index(a - 1, b)],
                               psi[maps.Index(a, b + 1)], psi[maps.Index(a, b - 1)], cu, cv);
      };
      const Eigen::Vector2d gh = gradient(m.h), gk = gradient(m.k);
      num += std::abs(gh.x() * gk.y() - gh.y() * gk.x());
      den += GradientNormProduct(gh, gk);
    }
  m.misalignment = den > 0.0 ? num / den : 0.0;
  for (double& x : m.h) x /= unit;
  for (double& x : m.k) x = x / unit / unit;
  const SampleMaps ref_maps = MakeSampleMaps(reference, su, sv);
  const Eigen::MatrixX3d p = maps.d[0] * surface.control, q = ref_maps.d[0] * reference.control;
  const Eigen::VectorXd deviation =
      (p - q).rowwise().stableNorm() / std::max(BoundingBoxDiagonal(q), 1e-300);
  m.max_deviation = deviation.maxCoeff(&m.worst_sample);
  m.mean_deviation = deviation.mean();
  return m;
}

NamedValues ToNamedValues(const WeingartenMeasures& m, bool with_relation) {
  NamedValues values = {{"misalignment", m.misalignment},
                        {"max_deviation", m.max_deviation},
                        {"mean_deviation", m.mean_deviation},
                        {"mean_abs_principal_curvature", m.mean_abs_principal_curvature}};
  if (with_relation) values.push_back({"max_relation_residual", m.max_relation_residual});
  return values;
}

WeingartenProblem::WeingartenProblem(const BSplineSurface& input, const WeingartenOptions& options)
    : options_(options), reference_(input) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid Weingarten options: " + why);
  ValidateBSpline(input);
  const int64_t su64 = options.samples_u > 0
                           ? options.samples_u
                           : static_cast<int64_t>(options.samples_per_control) * input.nu;
  const int64_t sv64 = options.samples_v > 0
                           ? options.samples_v
                           : static_cast<int64_t>(options.samples_per_control) * input.nv;
  if (su64 < 5 || sv64 < 5)
    throw InputError("at least 5 samples per direction are needed; got " + std::to_string(su64) +
                     " x " + std::to_string(sv64));
  if (su64 * sv64 > kMaxWeingartenSamples)
    throw InputError(std::to_string(su64) + " x " + std::to_string(sv64) + " samples: at most " +
                     std::to_string(kMaxWeingartenSamples) +
                     " are supported (each adds 12 unknowns and their rows)");
  const int su = static_cast<int>(su64), sv = static_cast<int>(sv64);
  maps_ = MakeSampleMaps(input, su, sv);
  ScaleToTargetCurvature();
  const std::vector<SampleTerms> stencils = AddCurvatureDefinitions();
  AddAlignment();
  if (options.geodesic_parallel_weight > 0.0) AddGeodesicParallel();
  AddRelations(stencils);
  tolerance_ = options.tolerance;
  if (tolerance_ == 0.0 && options.fixed_linear_relation && (linear_ || surface_linear_)) {
    const Eigen::Vector3d abc = LinearRelation();             // input units, a² + b² = 1
    const double k = options.target_mean_curvature * scale_;  // κ in input units
    tolerance_ = kDefaultRelationShare * (std::abs(abc[0]) * k + std::abs(abc[1]) * k * k);
  }
  AddControlNetTerms();
  if (options.prevent_folds) {
    fold_grid_ = GridNormals(input, kFoldGridFactor * su, kFoldGridFactor * sv);
    fold_cosine_ = std::min(kFoldCosine, MinNormalCosineAt(problem_.x()));
  }
}

// Scale: mean |principal curvature| at the samples = target (003 Table 1 note).
void WeingartenProblem::ScaleToTargetCurvature() {
  const BSplineSurface& input = reference_;
  const WeingartenOptions& options = options_;
  const int sv = maps_.sv;

  std::vector<double> h0, k0;  // at unit scale: the input divided by `unit`
  const double unit = SampleUnitCurvatures(input, maps_, &h0, &k0);
  for (int s = 0; s < maps_.num_samples(); ++s)
    if (!std::isfinite(h0[s]) || !std::isfinite(k0[s]))
      throw InputError("the surface is degenerate (s_u × s_v = 0) at sample " + std::to_string(s) +
                       " (u = " + std::to_string(maps_.u[s / sv]) +
                       ", v = " + std::to_string(maps_.v[s % sv]) + ")");
  const double mean = MeanAbsPrincipalCurvature(h0, k0);
  centre_ = input.control.colwise().mean().transpose();
  scale_ = (mean > 1e-12 ? mean / options.target_mean_curvature : 1.0) / unit;
  scaled_ = input;
  scaled_.control = (input.control.rowwise() - centre_.transpose()) * scale_;
}

// Blocks, the start x, the parameter rescaling and, per sample, the stencil and the 12
// auxiliary definitions of 003 §3.1.2.
std::vector<WeingartenProblem::SampleTerms> WeingartenProblem::AddCurvatureDefinitions() {
  const BSplineSurface& input = reference_;
  const WeingartenOptions& options = options_;
  const int su = maps_.su, sv = maps_.sv;
  VariableLayout& layout = problem_.layout();
  const int nc = input.num_control_points(), ns = maps_.num_samples();
  const bool gp = options.geodesic_parallel_weight > 0.0;
  control_block_ = layout.AddBlock("control points", nc, 3);
  if (options.curvature_auxiliaries) {
    // Only the sample's own definition rows touch the forms: eliminated before factorising.
    forms_block_ = layout.AddBlock("fundamental forms", ns, kFormsDim, /*eliminable=*/true);
    curvature_block_ = layout.AddBlock("curvatures", ns, kCurvatureDim);
  }
  if (gp) gradient_block_ = layout.AddBlock("gradient auxiliaries", ns, kGeodesicAuxDim);
  problem_.ResizeToLayout();
  Eigen::VectorXd& x = problem_.x();
  for (int i = 0; i < nc; ++i)
    x.segment<3>(layout.Index(control_block_, i, 0)) = scaled_.control.row(i).transpose();
  // Parameters are rescaled so that the mean speeds |s_u|, |s_v| are 1: E, F, G, Δ and n are
  // then O(1) and the definition rows are equally well conditioned for any knot domain.
  // H and K do not depend on the parametrisation.
  auto derivatives = SampleDerivatives(maps_, scaled_.control);
  double speed_u = 0.0, speed_v = 0.0;
  for (const auto& d : derivatives) {
    speed_u += d[0].norm() / ns;
    speed_v += d[1].norm() / ns;
  }
  speed_u = speed_u > 0.0 ? speed_u : 1.0;
  speed_v = speed_v > 0.0 ? speed_v : 1.0;
  derivative_scale_ = {1.0 / speed_u, 1.0 / speed_v, 1.0 / (speed_u * speed_u),
                       1.0 / (speed_u * speed_v), 1.0 / (speed_v * speed_v)};
  const auto& derivative_scale = derivative_scale_;
  for (auto& d : derivatives)
    for (int k = 0; k < 5; ++k) d[k] *= derivative_scale[k];
  inv_du_.assign(su, 0.0);
  inv_dv_.assign(sv, 0.0);
  for (int a = 1; a + 1 < su; ++a) inv_du_[a] = 1.0 / ((maps_.u[a + 1] - maps_.u[a - 1]) * speed_u);
  for (int b = 1; b + 1 < sv; ++b) inv_dv_[b] = 1.0 / ((maps_.v[b + 1] - maps_.v[b - 1]) * speed_v);

  // Auxiliary definitions, one element per sample.
  auto* definitions =
      options.curvature_auxiliaries
          ? problem_.AddFamily<CurvatureAuxiliaries>(Squared(options.definition_weight))
          : nullptr;
  std::vector<std::pair<std::vector<int>, SampleStencil>> stencils;  // per sample
  for (int s = 0; s < ns; ++s) {
    std::set<int> support;
    for (int k = 0; k < 6; ++k)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(maps_.d[k], s); it; ++it)
        support.insert(static_cast<int>(it.col()));
    SampleStencil stencil;
    stencil.control.assign(support.begin(), support.end());
    std::map<int, int> position;
    for (size_t j = 0; j < stencil.control.size(); ++j) position[stencil.control[j]] = j;
    for (int k = 0; k < 5; ++k) {
      stencil.weights[k].assign(stencil.control.size(), 0.0);
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(maps_.d[k + 1], s); it;
           ++it)
        stencil.weights[k][position[static_cast<int>(it.col())]] = it.value() * derivative_scale[k];
    }
    std::vector<int> items;
    for (int c : stencil.control) items.push_back(Items(control_block_)[c]);
    stencils.emplace_back(items, stencil);
    if (!definitions) continue;
    const int forms = Items(forms_block_)[s], curvature = Items(curvature_block_)[s];
    const Eigen::Matrix<double, 12, 1> exact = CurvatureAuxiliaries::ExactAuxiliary(derivatives[s]);
    const auto magnitudes =
        CurvatureAuxiliaries::RowMagnitudes(exact, options.target_mean_curvature);
    definitions->AddSample(forms, curvature, items, stencil, &magnitudes);
    SetSampleAuxiliaries(layout, s, exact, &x);
  }

  return stencils;
}

void WeingartenProblem::AddAlignment() {
  const WeingartenOptions& options = options_;
  VariableLayout& layout = problem_.layout();
  Eigen::VectorXd& x = problem_.x();
  const int su = maps_.su, sv = maps_.sv;
  auto aux = [this](int a, int b) { return CurvatureItem(a, b); };
  const bool definitions = options_.curvature_auxiliaries;
  // The alignment rows H_u K_v − H_v K_u are normalised by the RMS of |∇H| |∇K| over the inner
  // samples of the input (scaled units), so that ω_al weighs a dimensionless misalignment
  // against closeness and the auxiliary definitions whatever the parameter domain.
  double gradient_product = 0.0;
  int inner = 0;
  for (int a = 1; definitions && a + 1 < su; ++a)
    for (int b = 1; b + 1 < sv; ++b) {
      auto value = [&](int aa, int bb, int off) { return x[layout.ItemOffset(aux(aa, bb)) + off]; };
      auto gradient = [&](int off) {
        return CentralGradient(value(a + 1, b, off), value(a - 1, b, off), value(a, b + 1, off),
                               value(a, b - 1, off), inv_du_[a], inv_dv_[b]);
      };
      gradient_product +=
          Squared(GradientNormProduct(gradient(kCurvatureH), gradient(kCurvatureK)));
      ++inner;
    }
  alignment_scale_ =
      inner > 0 && gradient_product > 0.0 ? 1.0 / std::sqrt(gradient_product / inner) : 1.0;
  if (options.alignment_weight > 0.0) {
    auto* alignment = problem_.AddFamily<IsolineAlignment>(
        Squared(options.alignment_weight * (options.normalize_alignment ? 1.0 : alignment_scale_)),
        options.normalize_alignment);
    for (int a = 1; a + 1 < su; ++a)
      for (int b = 1; b + 1 < sv; ++b)
        alignment->AddSample(aux(a + 1, b), aux(a - 1, b), aux(a, b + 1), aux(a, b - 1), inv_du_[a],
                             inv_dv_[b]);
  }
}

// Geodesic parallel isolines (003 §3.2.1): gradient auxiliaries, their definitions and eq. 8.
void WeingartenProblem::AddGeodesicParallel() {
  const WeingartenOptions& options = options_;
  VariableLayout& layout = problem_.layout();
  Eigen::VectorXd& x = problem_.x();
  const int su = maps_.su, sv = maps_.sv;
  auto aux = [this](int a, int b) { return CurvatureItem(a, b); };
  auto* definitions2 = problem_.AddFamily<GeodesicAuxiliaries>(Squared(options.definition_weight));
  auto grad = [this](int a, int b) { return GradientItem(a, b); };
  for (int a = 1; a + 1 < su; ++a)
    for (int b = 1; b + 1 < sv; ++b) {
      const double cu = inv_du_[a];
      const double cv = inv_dv_[b];
      definitions2->AddSample(grad(a, b), FormsItem(a, b), aux(a + 1, b), aux(a - 1, b),
                              aux(a, b + 1), aux(a, b - 1), cu, cv);
    }
  // Exact initial values from the curvature auxiliaries, stored in units of the typical
  // |∇K|² and |∇H|².
  gradient_scales_ = {1.0, 1.0};
  SetGradientAuxiliaries(&x);
  double k_scale = 0.0, h_scale = 0.0;
  for (int a = 1; a + 1 < su; ++a)
    for (int b = 1; b + 1 < sv; ++b) {
      const auto g = x.segment<kGeodesicAuxDim>(layout.ItemOffset(grad(a, b)));
      k_scale += (g[kKuu] + g[kKvv]) / ((su - 2) * (sv - 2));
      h_scale += (g[kHuu] + g[kHvv]) / ((su - 2) * (sv - 2));
    }
  gradient_scales_ = {k_scale > 0.0 ? k_scale : 1.0, h_scale > 0.0 ? h_scale : 1.0};
  definitions2->SetGradientScales(gradient_scales_[0], gradient_scales_[1]);
  SetGradientAuxiliaries(&x);
  // Each row is divided by |∇‖∇ψ‖²| |∇ψ| at x^k (GeodesicParallelIsolines::Update): it is the
  // sine of the angle between the two gradients, like a normalised alignment row, and ω_gp
  // weighs it directly.
  auto* parallel =
      problem_.AddFamily<GeodesicParallelIsolines>(Squared(options.geodesic_parallel_weight));
  for (int a = 2; a + 2 < su; ++a)
    for (int b = 2; b + 2 < sv; ++b)
      parallel->AddSample({grad(a + 1, b), grad(a - 1, b), grad(a, b + 1), grad(a, b - 1)},
                          {aux(a + 1, b), aux(a - 1, b), aux(a, b + 1), aux(a, b - 1)}, inv_du_[a],
                          inv_dv_[b]);
}

void WeingartenProblem::AddRelations(const std::vector<SampleTerms>& stencils) {
  const WeingartenOptions& options = options_;
  const int ns = maps_.num_samples();
  if (options.linear_relation_weight > 0.0) {
    // Input units → scaled: κ_scaled = κ / scale, so a H + b K + c = 0 becomes
    // (a scale) H' + (b scale²) K' + c = 0.
    // Divided by its largest coefficient first (the same relation), so that coefficients of
    // any magnitude neither overflow nor underflow below.
    Eigen::Vector3d abc = options.linear_coefficients;
    if (abc.cwiseAbs().maxCoeff() > 0.0) abc /= abc.cwiseAbs().maxCoeff();
    abc = Eigen::Vector3d(abc[0] * scale_, abc[1] * scale_ * scale_, abc[2]);
    abc /= abc.head<2>().norm();
    if (options.fixed_linear_relation && options.relation_on_surface) {
      surface_linear_ = problem_.AddFamily<SurfaceLinearWeingarten>(
          Squared(options.linear_relation_weight), abc, options.target_mean_curvature);
      for (const auto& [items, stencil] : stencils) surface_linear_->AddSample(items, stencil);
    } else {
      linear_ = problem_.AddFamily<LinearWeingarten>(Squared(options.linear_relation_weight),
                                                     options.fixed_linear_relation, abc,
                                                     options.target_mean_curvature);
      for (int s = 0; s < ns; ++s) linear_->AddSample(Items(curvature_block_)[s]);
    }
  }
  if (options.bspline_relation_weight > 0.0) {
    auto* curve = problem_.AddFamily<CurvatureCurveRelation>(
        Squared(options.bspline_relation_weight), options.bspline_relation_control_points);
    for (int s = 0; s < ns; ++s) curve->AddSample(Items(curvature_block_)[s]);
  }
}

// Closeness, shape preservation, fairness and boundary gliding on the control net.
void WeingartenProblem::AddControlNetTerms() {
  const BSplineSurface& input = reference_;
  const WeingartenOptions& options = options_;
  const int nc = input.num_control_points();
  auto control = [&](int i, int j) { return Items(control_block_)[scaled_.Index(i, j)]; };
  // Closeness and gliding are measured in units of the control net's mean edge length, so their
  // weights do not depend on the surface's size or on the net's resolution.
  double edge_sum = 0.0;
  int edges = 0;
  for (int i = 0; i < input.nu; ++i)
    for (int j = 0; j < input.nv; ++j) {
      const Eigen::RowVector3d c = scaled_.control.row(scaled_.Index(i, j));
      if (i + 1 < input.nu) edge_sum += (scaled_.control.row(scaled_.Index(i + 1, j)) - c).norm();
      if (j + 1 < input.nv) edge_sum += (scaled_.control.row(scaled_.Index(i, j + 1)) - c).norm();
      edges += (i + 1 < input.nu) + (j + 1 < input.nv);
    }
  const double mean_edge = edges > 0 && edge_sum > 0.0 ? edge_sum / edges : 1.0;
  if (options.closeness_weight > 0.0) {
    auto* closeness = problem_.AddFamily<Closeness>(
        3, Squared(options.soft_start * options.closeness_weight / mean_edge));
    for (int i = 0; i < nc; ++i) {
      const Eigen::Vector3d p = scaled_.control.row(i).transpose();
      closeness->AddTarget(Items(control_block_)[i], p.data());
    }
  }
  if (options.shape_weight > 0.0) {
    auto* shape = problem_.AddFamily<EdgeLengthPreservation>(
        Squared(options.soft_start * options.shape_weight));
    auto add = [&](int i0, int j0, int i1, int j1) {
      const double l =
          (scaled_.control.row(scaled_.Index(i0, j0)) - scaled_.control.row(scaled_.Index(i1, j1)))
              .norm();
      if (l > 0.0) shape->AddEdge(control(i0, j0), control(i1, j1), l);
    };
    for (int i = 0; i < input.nu; ++i)
      for (int j = 0; j < input.nv; ++j) {
        if (i + 1 < input.nu) add(i, j, i + 1, j);
        if (j + 1 < input.nv) add(i, j, i, j + 1);
        if (i + 1 < input.nu && j + 1 < input.nv) {
          add(i, j, i + 1, j + 1);
          add(i + 1, j, i, j + 1);
        }
      }
  }
  if (options.solver.fairness_weight > 0.0) {
    // 003 §3.3: ‖c_ij − (c_i,j−1 + c_i,j+1)/2‖² = ¼ ‖second difference‖², both directions.
    auto* fairness = problem_.AddFamily<PolylineFairness>(2, 3, 0.25);
    for (int i = 0; i < input.nu; ++i)
      for (int j = 1; j + 1 < input.nv; ++j)
        fairness->AddElement({control(i, j - 1), control(i, j), control(i, j + 1)});
    for (int j = 0; j < input.nv; ++j)
      for (int i = 1; i + 1 < input.nu; ++i)
        fairness->AddElement({control(i - 1, j), control(i, j), control(i + 1, j)});
  }
  if (options.boundary_weight > 0.0) AddBoundaryGliding(mean_edge);
}

// Boundary control points glide on the reference's boundary polygon; the corners are held.
void WeingartenProblem::AddBoundaryGliding(double mean_edge) {
  const BSplineSurface& input = reference_;
  const WeingartenOptions& options = options_;
  auto control = [&](int i, int j) { return Items(control_block_)[scaled_.Index(i, j)]; };
  auto* glide = problem_.AddFamily<PolylineGliding>(Squared(options.boundary_weight / mean_edge));
  // Held like the gliding rows, whatever the soft schedule does to closeness.
  auto* corners = problem_.AddFamily<Closeness>(3, Squared(options.boundary_weight / mean_edge),
                                                "boundary corners", FamilyRole::kConstraint);
  auto row = [&](int i0, int j0, int di, int dj, int count) {
    std::vector<Eigen::Vector3d> line;
    for (int t = 0; t < count; ++t)
      line.push_back(scaled_.control.row(scaled_.Index(i0 + t * di, j0 + t * dj)).transpose());
    return line;
  };
  const int nu = input.nu, nv = input.nv;
  const std::vector<Eigen::Vector3d> sides[4] = {row(0, 0, 0, 1, nv), row(nu - 1, 0, 0, 1, nv),
                                                 row(0, 0, 1, 0, nu), row(0, nv - 1, 1, 0, nu)};
  for (int j = 1; j + 1 < nv; ++j) {
    glide->AddPoint(control(0, j), sides[0]);
    glide->AddPoint(control(nu - 1, j), sides[1]);
  }
  for (int i = 1; i + 1 < nu; ++i) {
    glide->AddPoint(control(i, 0), sides[2]);
    glide->AddPoint(control(i, nv - 1), sides[3]);
  }
  for (auto [i, j] : {std::pair{0, 0}, {0, nv - 1}, {nu - 1, 0}, {nu - 1, nv - 1}}) {
    const Eigen::Vector3d p = scaled_.control.row(scaled_.Index(i, j)).transpose();
    corners->AddTarget(control(i, j), p.data());
  }
}

void WeingartenProblem::SetSampleAuxiliaries(const VariableLayout& layout, int s,
                                             const Eigen::Matrix<double, 12, 1>& a,
                                             Eigen::VectorXd* x) const {
  x->segment<kFormsDim>(layout.Index(forms_block_, s, 0)) = a.head<kFormsDim>();
  x->segment<kCurvatureDim>(layout.Index(curvature_block_, s, 0)) = a.tail<kCurvatureDim>();
}

void WeingartenProblem::GatherControlPoints(const Eigen::VectorXd& x) const {
  const VariableLayout& layout = problem_.layout();
  // Sized once: this runs after every step.
  const int nc = reference_.num_control_points();
  control_buffer_.resize(nc, 3);
  for (int i = 0; i < nc; ++i)
    control_buffer_.row(i) = x.segment<3>(layout.Index(control_block_, i, 0)).transpose();
}

double WeingartenProblem::MinNormalCosineAt(const Eigen::VectorXd& x) const {
  GatherControlPoints(x);
  return fold_grid_.MinCosine(control_buffer_).min_cosine;
}

void WeingartenProblem::SetCurvatureAuxiliaries(Eigen::VectorXd* x) const {
  if (curvature_block_ < 0) return;
  const VariableLayout& layout = problem_.layout();
  // Buffers sized once: this runs after every step.
  const int ns = maps_.num_samples();
  GatherControlPoints(*x);
  for (int k = 0; k < 5; ++k) {
    derivative_buffer_[k].resize(ns, 3);
    derivative_buffer_[k].noalias() = maps_.d[k + 1] * control_buffer_;
  }
  std::array<Eigen::Vector3d, 5> d;
  for (int s = 0; s < ns; ++s) {
    for (int k = 0; k < 5; ++k)
      d[k] = derivative_buffer_[k].row(s).transpose() * derivative_scale_[k];
    SetSampleAuxiliaries(layout, s, CurvatureAuxiliaries::ExactAuxiliary(d), x);
  }
}

void WeingartenProblem::SetGradientAuxiliaries(Eigen::VectorXd* x) const {
  if (gradient_block_ < 0) return;
  const VariableLayout& layout = problem_.layout();
  auto value = [&](int a, int b, int off) {
    return (*x)[layout.ItemOffset(CurvatureItem(a, b)) + off];
  };
  for (int a = 1; a + 1 < maps_.su; ++a)
    for (int b = 1; b + 1 < maps_.sv; ++b) {
      const double* forms = x->data() + layout.ItemOffset(FormsItem(a, b));
      const double E = forms[kE], F = forms[kF], G = forms[kG], D = forms[kDelta];
      Eigen::Matrix<double, kGeodesicAuxDim, 1> g;
      for (int p = 0; p < 2; ++p) {
        const int off = p == 0 ? kCurvatureK : kCurvatureH;
        const Eigen::Vector2d gradient =
            CentralGradient(value(a + 1, b, off), value(a - 1, b, off), value(a, b + 1, off),
                            value(a, b - 1, off), inv_du_[a], inv_dv_[b]);
        const double du = gradient.x(), dv = gradient.y();
        const double unit = gradient_scales_[p];
        g[3 * p] = du * du / unit;
        g[3 * p + 1] = du * dv / unit;
        g[3 * p + 2] = dv * dv / unit;
        g[6 + p] = (G * du * du - 2 * F * du * dv + E * dv * dv) / (D * unit);
      }
      x->segment<kGeodesicAuxDim>(layout.Index(gradient_block_, maps_.Index(a, b), 0)) = g;
    }
}

SolverOptions WeingartenProblem::solver_options() const {
  SolverOptions s = options_.solver;
  s.fairness_weight *= options_.soft_start;
  if (options_.soft_start > 1.0) {
    s.soft_weight_floor = 1.0 / (options_.soft_start * options_.soft_start);
  } else {
    s.soft_weight_decay = 1.0;  // fixed weights
    s.soft_weight_floor = 0.0;
  }
  if (options_.project_auxiliaries)
    s.project_trial = [this](Eigen::VectorXd* x) {
      SetCurvatureAuxiliaries(x);
      SetGradientAuxiliaries(x);
    };
  if (options_.prevent_folds)
    s.admissible_trial = [this](const Eigen::VectorXd& x) {
      return MinNormalCosineAt(x) >= fold_cosine_;
    };
  return s;
}

CeresOptions WeingartenProblem::ceres_options(int max_iterations) const {
  const SolverOptions s = solver_options();
  return CeresOptionsFor(s, max_iterations, options_.soft_start > 1.0 ? s.soft_weight_floor : 1.0);
}

NamedValues WeingartenProblem::MeasureAt(const Eigen::VectorXd& x) const {
  return ToNamedValues(MeasuresAt(x), linear_ || surface_linear_);
}

bool WeingartenProblem::MeetsTolerance(const NamedValues& measures) const {
  return ValueOf(measures, options_.target_measure()) <= tolerance_;
}

BSplineSurface WeingartenProblem::ScaledToInput(const Eigen::VectorXd& x) const {
  BSplineSurface out = reference_;
  const VariableLayout& layout = problem_.layout();
  for (int i = 0; i < out.num_control_points(); ++i)
    out.control.row(i) =
        (x.segment<3>(layout.Index(control_block_, i, 0)) / scale_ + centre_).transpose();
  return out;
}

BSplineSurface WeingartenProblem::Result() const { return ScaledToInput(problem_.x()); }

Eigen::Vector3d WeingartenProblem::LinearRelation() const {
  if (!linear_ && !surface_linear_) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d abc = linear_ ? linear_->coefficients() : surface_linear_->coefficients();
  Eigen::Vector3d input(abc[0] / scale_, abc[1] / (scale_ * scale_), abc[2]);
  return input / input.head<2>().norm();
}

WeingartenMeasures WeingartenProblem::MeasuresAt(const Eigen::VectorXd& x) const {
  WeingartenMeasures m = MeasureWeingarten(ScaledToInput(x), reference_, maps_.su, maps_.sv);
  if (linear_ || surface_linear_) {
    const Eigen::Vector3d abc = LinearRelation();
    for (size_t s = 0; s < m.h.size(); ++s)
      m.max_relation_residual =
          std::max(m.max_relation_residual, std::abs(abc[0] * m.h[s] + abc[1] * m.k[s] + abc[2]));
  }
  return m;
}

}  // namespace gproj::weingarten
