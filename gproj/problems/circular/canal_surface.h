#pragma once
// Canal surfaces from a circular strip (000 §3.2–3.3, §4.1).
//
// Strip (000 Fig. 6): points P_0..P_n on a curve, a point P that fixes the first circle (through
// P_0, P_1, P), and the lengths L_k = |P_k Q_k| of the edges across the strip. Propagation: Q_0
// is the point of the first circle at chord L_0 from P_0; then Q_{k+1} is the point of the
// circle through P_k, P_{k+1}, Q_k at chord L_{k+1} from P_{k+1}. Every quad
// (P_k, P_{k+1}, Q_{k+1}, Q_k) is circular by construction, convex (cyclic order kept).
//
// Cyclidic net: an orthonormal frame (t1, t2, n) at P_0 is carried to every vertex by
// reflection in the bisector plane of each edge (consistent around circular quads). The edge
// a → b becomes the circular arc through a and b tangent at a to the frame's t1 (edges along
// the strip) or t2 (edges across it); 1 / R_edge = 2 |t × (b − a)| / |b − a|². The arcs across
// the strip, extended to full circles C_k, are one family of curvature circles of the canal
// surface; consecutive C_k lie on a common sphere.
//
// Shape smoothing (000 eq. 5): F = Σ_edges 1 / R_edge² over the strip's edges, minimised over
// the lengths L and the frame at P_0 (normal by the angles λ, θ as in the paper, plus the
// rotation ψ of t1 about the normal, the frame's third degree of freedom), the curve points
// kept (the curve is fitted exactly). Ceres' line-search BFGS does the minimisation, with
// gradients by automatic differentiation.
//
// Meshing between co-spherical circles (000 §4.1, Fig. 13): the arc of C_0 from P_0 to Q_0 is
// divided into m equal angles; P_{k+1,j+1} is the second intersection of the plane through
// P_{k,j}, P_{k,j+1}, P_{k+1,j} with C_{k+1}, starting from P_{k+1,0} = P_{k+1}. Every quad of
// the result is circular (planar, and its vertices lie on the sphere through C_k and C_{k+1}).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/circle.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj::circular {

struct CircularStripInput {
  std::vector<Eigen::Vector3d> curve;                     // P_0..P_n, n ≥ 1
  Eigen::Vector3d first_point = Eigen::Vector3d::Zero();  // P
  std::vector<double> lengths;                            // L_0..L_n (> 0)
};

// The input from a curve, a first point and the lengths: `lengths` (one per curve point) or one
// `length` (> 0) for all, not both. Throws InputError "give either `lengths` or `length`,
// not both", "give the lengths ...", "`lengths` needs one value per curve point (N), got M".
CircularStripInput MakeCircularStripInput(std::vector<Eigen::Vector3d> curve,
                                          const Eigen::Vector3d& first_point,
                                          const std::vector<double>& lengths, double length);

struct CircularStrip {
  std::vector<Eigen::Vector3d> p, q;  // n + 1 each
};

// Throws InputError naming the point or the length index that breaks the construction: fewer
// than two points, collinear P_0, P_1, P, a length that is not positive or longer than the
// circle's diameter, or a Q_{k+1} that would pass Q_k (the quad would fold).
CircularStrip BuildCircularStrip(const CircularStripInput& input);

// The strip as a quad mesh: vertex (0, k) = P_k, (1, k) = Q_k (grid order, 1 × n faces).
PolyMesh StripMesh(const CircularStrip& strip);

// Frame at P_0 from the angles: n = (cos λ cos θ, cos λ sin θ, sin λ); t1 = the projection of
// P_1 − P_0 onto the plane ⟂ n, rotated by ψ about n; t2 = n × t1.
struct FrameAngles {
  double lambda = 0.0, theta = 0.0, psi = 0.0;
};
// Angles whose normal is `normal` (normalised) and ψ = 0.
FrameAngles AnglesFromNormal(const Eigen::Vector3d& normal);
// The unit normal n of the angles.
Eigen::Vector3d NormalOf(const FrameAngles& angles);

struct Frame {
  Eigen::Vector3d t1, t2, n;
};
// Throws InputError unless the normal of `angles` leaves the chord `from` → `to` (the first
// edge, whose projection gives the frame's first tangent) by more than 1e-6 rad, and is finite.
void CheckFrameNormal(const FrameAngles& angles, const Eigen::Vector3d& from,
                      const Eigen::Vector3d& to);

// The frame of `angles` at P_0 of `curve` (as MakeCyclidicStrip sets it up), and the angles of a
// right-handed orthonormal frame (t2 = n × t1; ψ takes up the turn of t1 about n).
Frame FrameOfAngles(const std::vector<Eigen::Vector3d>& curve, const FrameAngles& angles);
FrameAngles AnglesOfFrame(const std::vector<Eigen::Vector3d>& curve, const Frame& frame);

struct CyclidicStrip {
  CircularStrip strip;
  std::vector<Frame> p_frames, q_frames;  // at P_k and Q_k
  std::vector<Circle> circles;            // C_k: through P_k and Q_k, tangent to t2 at P_k
  double energy = 0.0;                    // F of 000 eq. 5
};
CyclidicStrip MakeCyclidicStrip(const CircularStrip& strip, const FrameAngles& angles);

// Canal mesh: (n + 1) × (m + 1) vertices, vertex (k, j) = P_{k,j}; grid order as above.
// Throws InputError if a plane is parallel to a circle's plane (degenerate step).
PolyMesh MeshCanalSurface(const CyclidicStrip& net, int m);

// The canal mesh's rows: row k holds P_{k,0..m} on C_k (n + 1 rows).
std::vector<std::vector<Eigen::Vector3d>> CanalRows(const CyclidicStrip& net, int m);

// A grid mesh of rows of equal length: faces (k, j), (k + 1, j), (k + 1, j + 1), (k, j + 1);
// with `ring` also from the last row to the first.
PolyMesh RowsMesh(const std::vector<std::vector<Eigen::Vector3d>>& rows, bool ring);

// The normal at P_0 at a fixed angle to a reference plane (000 §3.3: "the user can specify
// additional constraints, like the angle made by the normal and a reference plane. In the
// latter case, the degrees of freedom λ and θ become coupled, and the normal rotates along a
// cone"): the normals n with asin(n · axis) = angle, a cone about the plane's normal `axis`.
struct NormalCone {
  bool enabled = false;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // the reference plane's normal
  double angle_deg = 0.0;                           // the normal's angle to the plane
  // Finite, non-zero axis; |angle| ≤ 89° (at 90° the cone is one normal: give it as `normal`).
  bool IsValid(std::string* why) const;
  // An orthonormal basis (e1, e2) of the plane, and the cone's normal at turn φ about the axis
  // (φ = 0 along e1).
  void Basis(Eigen::Vector3d* e1, Eigen::Vector3d* e2) const;
  Eigen::Vector3d NormalAt(double phi) const;
  // The turn φ of n's projection onto the plane (0 when n is along the axis): NormalAt(Turn(n))
  // is the normal on the cone nearest to n.
  double Turn(const Eigen::Vector3d& n) const;
  // The angle of n to the plane, degrees.
  double AngleOf(const Eigen::Vector3d& n) const;
};

// `angles` with the normal moved to the nearest normal on `cone` (ψ kept).
FrameAngles OnCone(const FrameAngles& angles, const NormalCone& cone);

struct CanalSmoothingOptions {
  int max_iterations = 200;
  // Weight of Σ (L_k / L_k⁰ − 1)², which keeps the lengths near the input; the energy term is
  // F · ℓ² / #edges with ℓ the mean edge length of the input strip (scale-free).
  double length_weight = 0.1;
  bool optimize_lengths = true;
  bool optimize_frame = true;
  // With cone.enabled the frame's normal stays on the cone: the frame's free parameters are its
  // turn about the cone's axis and ψ (the start normal is moved onto the cone first).
  NormalCone cone;
  // The smoothing's tolerance: BFGS stops, converged, when an iteration lowers the objective by
  // less than this fraction (Ceres' function tolerance; its gradient and parameter tolerances
  // keep Ceres' defaults and also count as converged).
  double function_tolerance = 1e-6;
  bool IsValid(std::string* why) const;
};

struct CanalSmoothingSummary {
  bool converged = false;
  int iterations = 0;
  double initial_energy = 0.0, final_energy = 0.0;  // F of eq. 5 (not the scaled objective)
  std::string termination;                          // e.g. "ceres-bfgs CONVERGENCE: …"
  std::string message;                              // Ceres' report line
  std::vector<double> lengths;
  FrameAngles angles;
  // Per iterate: the objective as energy, Ceres' step and time, F as smoothness_energy.
  std::vector<RunRecord> history;
};

// Minimises the smoothing objective from `input` and `angles` by Ceres' line-search BFGS.
// `callback` gets every iterate's record (may be empty); returning false stops the run.
CanalSmoothingSummary SmoothCanalStrip(const CircularStripInput& input, const FrameAngles& angles,
                                       const CanalSmoothingOptions& options,
                                       const RunCallback& callback = nullptr);

// The frame's default normal at P_0: in the first quad's plane, across the curve (towards Q_0),
// so that the crossing arcs leave the strip's plane.
Eigen::Vector3d DefaultCanalNormal(const CircularStrip& strip);

struct CanalSurfaceOptions {
  bool smooth = false;  // minimise 000 eq. 5 before meshing
  CanalSmoothingOptions smoothing;
  int segments = 12;  // quads across the strip in the canal mesh, in [1, 100000]
  bool IsValid(std::string* why) const;
};

// A canal surface as one run: the strip from its input (the build step), the cyclidic net of a
// frame, an optional smoothing, and the mesh. Measures: smoothness_energy (F of 000 eq. 5) and
// MeasureCircularMesh's measures of the canal mesh.
class CanalSurface {
 public:
  // Throws InputError for invalid options or an input BuildCircularStrip refuses.
  CanalSurface(const CircularStripInput& input, const FrameAngles& angles,
               const CanalSurfaceOptions& options);

  // With options.smooth: SmoothCanalStrip (solver ceres, method BFGS; converged when its
  // tolerance is met; the history's measures are smoothness_energy only). Without: a
  // construction (closed form), no iterations, converged. Initial and final measures are Measure()
  // before and after (initial: smoothness_energy only when the starting net cannot be meshed).
  // Throws InputError when the final net cannot be meshed.
  RunReport Run(const RunCallback& callback = nullptr);
  NamedValues Measure() const;

  const CircularStripInput& input() const { return input_; }  // with the current lengths
  const FrameAngles& angles() const { return angles_; }
  const CircularStrip& strip() const { return strip_; }
  CyclidicStrip Net() const { return MakeCyclidicStrip(strip_, angles_); }
  PolyMesh Mesh() const { return MeshCanalSurface(Net(), options_.segments); }

 private:
  RunReport Smooth(const RunCallback& callback);

  CanalSurfaceOptions options_;
  CircularStripInput input_;
  FrameAngles angles_;
  CircularStrip strip_;
};

}  // namespace gproj::circular
