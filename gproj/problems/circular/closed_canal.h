#pragma once
// Closed canal strips (000 §4.2, Fig. 14).
//
// The curve P_0..P_{N−1} is closed by the edge P_{N−1} → P_0, so the strip has N quads
// (P_k, P_{k+1}, Q_{k+1}, Q_k), indices mod N. As for open strips (canal_surface.h) the first
// point P fixes the first circle Γ_0 = (P_0, P_1, P), the length L_0 picks Q_0 on it and L_k
// picks Q_k on Γ_{k−1} for k = 1..N−2. The closing quad (P_{N−1}, P_0, Q_0, Q_{N−1}) must be
// circular too, and its circle meets Γ_0 in P_0, Q_0 and Γ_{N−2} in P_{N−1}, Q_{N−1}:
//   case 1: Γ_0 and Γ_{N−2} lie on one sphere. The closing circle is the circle through Q_0, P_0
//           and P_{N−1} (it stays on that sphere); only Q_{N−1} is set by the closing.
//   case 2: otherwise the closing circle is the intersection of the spheres (Γ_0, P_{N−1}) and
//           (Γ_{N−2}, P_0), the only circle that closes the strip: Q_0 is moved to its second
//           intersection with Γ_0 (the start cannot be prescribed), Q_{N−1} likewise on Γ_{N−2}.
// Q_1..Q_{N−2} do not depend on Q_0 (each Γ_k is fixed by P and the lengths), so the closing
// leaves them where they are. L_{N−1} (and in case 2 L_0) are the closing's, not the input's.
//
// A closed cyclidic net: the frame at P_0 is carried around the curve by the reflections in the
// edges' bisector planes, whose linear parts compose to an orthogonal map M. Each reflection
// reverses t1's sense of travel and keeps t2 and n, so the net closes smoothly only when
// M t1 = (−1)^N t1, M t2 = t2 and M n = n: M = I for an even count, the reflection in the plane
// normal to t1 for an odd one. (For a curve inscribed in a sphere M fixes the sphere's normal at
// P_0, so with an odd count M is always such a reflection: 000 §4.2's pseudo-spherical curves.)
// Where a closing frame exists, the frame nearest the asked one is taken.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "gproj/problems/circular/canal_surface.h"
#include "gproj/problems/run/construction.h"

namespace gproj::circular {

struct ClosedCircularStrip {
  CircularStrip strip;  // N points in p and q
  int closing_case = 0;
  Circle closing_circle;
  // Distance of Γ_{N−2} from the sphere through Γ_0 and P_{N−1}, over the mean edge length of
  // the strip (case 1 below 1e-9).
  double cosphericity = 0.0;
  double start_shift = 0.0;  // |Q_0 − the Q_0 of L_0| (0 in case 1)
};

// `input.curve` has N ≥ 3 points without the repeated first point; `input.lengths` N values
// (L_{N−1}, and in case 2 L_0, are replaced by the closing's). Case 1 when Γ_{N−2} is within
// `cospherical_tolerance` (of the mean edge) of the sphere through Γ_0 and P_{N−1}: rounded
// input of a co-spherical design stays in case 1 (case 2 is discontinuous there: it moves Q_0 by
// the size of the strip however small the miss), its closing quad then circular to about that
// tolerance. Runs about P_0 (the result is the same far from the origin). Throws InputError naming
// the point or quad that breaks the construction: fewer than three points, a repeated point, the
// open strip's errors, a closing circle that degenerates to a line or touches Γ_0 or Γ_{N−2}
// only at P_0 or P_{N−1}, or a quad the closing folds.
ClosedCircularStrip BuildClosedCircularStrip(const CircularStripInput& input,
                                             double cospherical_tolerance = 1e-6);

// The closed strip as a ring of N quads (P_k, P_{k+1}, Q_{k+1}, Q_k): vertex 2k = P_k, 2k + 1 =
// Q_k.
PolyMesh ClosedStripMesh(const CircularStrip& strip);

// The linear part of the reflections in the bisector planes of the edges P_k P_{k+1}, k = 0..N−1
// (indices mod N), in order: it carries the frame at P_0 around the curve back to P_0.
Eigen::Matrix3d LoopReflection(const std::vector<Eigen::Vector3d>& closed_curve);

// Largest angle (degrees) between a frame axis and its image under `loop`, with t1's sense
// reversed for an odd count (det loop = −1).
double FrameClosureAngle(const Eigen::Matrix3d& loop, const Frame& frame);

// The frame nearest to `start` that closes under `loop` (see above) when one does: for an odd
// count, `start` turned the least to put t1 on the normal of the mirror plane nearest to `loop`
// (the eigenvector of its symmetric part's least eigenvalue); for an even count `start` (only
// loop = I closes, whatever the frame). Whether it closes is FrameClosureAngle's to say (rounded
// input of a pseudo-spherical curve closes to about its rounding). `rotation_deg` gets the
// angle between `start` and the result.
Frame ClosingFrame(const Eigen::Matrix3d& loop, const Frame& start, double* rotation_deg);

// The largest seam gap (per mean edge) that BuildClosedCanalSurface welds when the frame closes.
constexpr double kWeldTolerance = 1e-5;

struct ClosedCanalOptions {
  int segments = 12;                    // quads across the strip in the canal mesh, in [1, 100000]
  double cospherical_tolerance = 1e-6;  // see BuildClosedCircularStrip
  double frame_tolerance_deg = 1e-3;    // the frame closes when it misses itself by at most this
  // Close the frame when the curve allows it (else the asked frame is kept and the report
  // gives how far it turns around the loop).
  bool close_frame = true;
  bool IsValid(std::string* why) const;
};

// A closed canal surface as one construction: the closed strip, the (closing) frame, the cyclidic
// net once around the curve (N + 1 points, the last P_0 again with the carried frame, so its
// circle is C_0 when the frame closes) and its canal mesh, N × segments circular quads. The
// mesh's rows are welded into a ring when the frame and the curvature lines close (seam gap at
// most kWeldTolerance of the mean edge length); otherwise the last row stays apart and the gap is
// reported. Runs about P_0.
struct ClosedCanalSurface {
  ClosedCircularStrip closed;
  FrameAngles angles;
  CyclidicStrip net;
  PolyMesh mesh;
  bool frame_closes = false;
  bool welded = false;
  // closing_case, cosphericity, start_point_shift, last_length, frame_closure_deg,
  // frame_rotation_deg, seam_gap, then MeasureCircularMesh of the mesh.
  NamedValues measures;
};

// Throws InputError for invalid options or input.
ClosedCanalSurface BuildClosedCanalSurface(const CircularStripInput& input,
                                           const FrameAngles& angles,
                                           const ClosedCanalOptions& options);

// The frame's default normal on a closed curve: DefaultCanalNormal of the open strip on
// P_0..P_{N−2}. Throws InputError as BuildCircularStrip does.
Eigen::Vector3d DefaultClosedCanalNormal(const CircularStripInput& input);

// Why a canal mesh of a circular strip has crossed quads (CrossedQuadsFault's hint).
inline constexpr const char* kCrossedQuadsHint =
    "the frame makes the plane steps between the circles pass each other; try another `normal` "
    "or `psi`";

// The run's report from `construction` (timed from before the build), converged when the ring
// closes (the frame and the curvature lines) and no quad is crossed; the termination says why
// not.
RunReport ClosedCanalRunReport(const ClosedCanalSurface& surface, const ClosedCanalOptions& options,
                               const Construction& construction);

// The report's extra keys: frame (λ, θ, ψ, normal), closing_circle (centre, normal, radius),
// lengths (|P_k Q_k|), mesh (rows, segments, closed).
nlohmann::json ClosedCanalJson(const ClosedCanalSurface& surface,
                               const ClosedCanalOptions& options);

}  // namespace gproj::circular
