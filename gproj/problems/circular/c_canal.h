#pragma once
// C-canal surfaces (000 §5.2, eq. 10, Fig. 21): the Combescure transformation of a canal surface
// that keeps the guide curve P_k and maps the canal's first circle (the arc from P_0 to Q_0) to
// a planar cross-section — the arc's edges scaled by given factors s_j, a Combescure transform
// of the circle. The designer gives the lengths L_k = |P_k Q'_k| of the C-canal itself; only the
// canal surface can be built from lengths (000 §3.2), and after the transformation its lengths
// L'_k differ. The canal's lengths ℓ are therefore found by Ceres' line-search BFGS minimising
//   E(ℓ) = Σ_k (L'_k(ℓ) − L_k)²                                              (000 eq. 10)
// (all at once; the paper optimises each L_k in turn), with ℓ_k = L_k e^{u_k} so they stay
// positive and numeric central differences for the gradient. The result is a circular mesh
// (Combescure transformations keep circles: 000 §2.4).

#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/circular/canal_surface.h"

namespace gproj::circular {

struct CCanalOptions {
  int segments = 12;                   // quads across the strip (the cross-section's edges)
  std::vector<double> section_scales;  // s_j > 0, one per segment: the cross-section's edges
  int max_iterations = 200;
  double length_tolerance = 1e-9;  // converged when max |L'_k − L_k| ≤ this × mean L
  bool IsValid(std::string* why) const;
};

struct CCanalSurface {
  PolyMesh mesh;                      // the C-canal: (n + 1) × (segments + 1) grid, vertex (k, j)
  PolyMesh canal;                     // the canal surface it is the Combescure transform of
  std::vector<double> canal_lengths;  // ℓ found
  std::vector<double> lengths;        // L'_k of the result
  double max_length_error = 0.0;      // max |L'_k − L_k| / mean L
  double initial_length_error = 0.0;  // the same with ℓ = L (no optimisation)
  int iterations = 0;
  bool converged = false;
  std::string message;  // Ceres' report line
};

// `input.lengths` are the C-canal's target lengths L_k; `angles` the frame at P_0. Throws
// InputError for invalid options (naming the rule), a scale count other than `segments`, or a
// strip or mesh the canal construction refuses at the start.
CCanalSurface BuildCCanalSurface(const CircularStripInput& input, const FrameAngles& angles,
                                 const CCanalOptions& options);

}  // namespace gproj::circular
