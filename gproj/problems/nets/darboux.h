#pragma once
// Darboux cyclide skins: the image of an H-net under an inversion (004 §4 as its abstract
// states it; Pottmann, Shi, Skopenkov 2012). An inversion x ↦ c + r² (x − c) / |x − c|² maps
// every quadric patch of an H-net to a patch of a Darboux cyclide and every ruling to a circle
// through c; it is conformal, so the patches still join with the H-net's tangent-plane
// continuity. Each rational bilinear patch maps exactly to a rational biquadratic patch. The
// Gaussian curvature changes sign where the inversion's shift of the principal curvatures
// outweighs them: κ' = a κ + b with a = |x − c|² / r², b = 2 ⟨x − c, n⟩ / r² (κ with respect to
// the normal n; the sign of κ' is up to the image's orientation), so a skin can have K > 0 where
// the H-net had K < 0.
//
// What this is not: one inversion maps the whole H-net, so all circles of a skin pass through
// the one centre c, and a skin is the H-net up to a conformal map. Whether the paper's
// "freeform deformations based on Darboux transformations" are more general is not known from
// its seed text.

#include <Eigen/Core>
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/surface/rational_bezier.h"
#include "gproj/problems/nets/hnet_json.h"

namespace gproj::nets {

struct Inversion {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 1.0;
  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const;
};

// The patch of face f (004 eq. 1) as a rational Bézier patch of degree (1, 1): the face's
// corners 0..3 at (u, v) = (0, 0), (1, 0), (1, 1), (0, 1), as EvaluatePatch places them.
RationalBezierPatch HNetPatch(const PolyMesh& mesh, PolyMesh::FaceHandle f,
                              const std::array<double, 4>& weights);

// The image of a rational Bézier patch of degree (m, n) under the inversion, exactly: a
// rational patch of degree (2m, 2n) (numerator c |Q|² + r w Q, denominator |Q|², with
// Q = (x − c) w / r), the same parameters mapping to the inverted points.
RationalBezierPatch InvertPatch(const RationalBezierPatch& patch, const Inversion& inversion);

// The point of the patchwork nearest to p: its distance, the face and the parameters there
// (each patch sampled on a 16 × 16 grid, the nearest samples refined by projection).
struct NearestPatchPoint {
  double distance = 0.0;
  int face = -1;
  double u = 0.0, v = 0.0;
};
NearestPatchPoint FindNearestPatchPoint(const std::vector<RationalBezierPatch>& patches,
                                        const Eigen::Vector3d& p);

// The centre must lie this far off the H-net (× its bounding-box diagonal): nearer, the skin
// reaches beyond ~1 / kMinCentreDistance times the radius² / diagonal, and on the surface it is
// unbounded.
inline constexpr double kMinCentreDistance = 1e-3;
// The centre at most this many diagonals from the H-net's box centre (farther, the inversion is
// nearly a similarity and its cancellations cost the skin's precision), and the radius within
// this range of diagonals.
inline constexpr double kMaxCentreDistance = 1e3;
inline constexpr double kRadiusRange[2] = {1e-6, 1e6};

struct DarbouxSkin {
  Inversion inversion;
  std::vector<RationalBezierPatch> hnet_patches;  // degree (1, 1), one per face
  std::vector<RationalBezierPatch> patches;       // degree (2, 2), their images
  NearestPatchPoint nearest;                      // the H-net's point nearest the centre
};

// The skin of an H-net. Throws InputError (naming `centre` and `radius` as options) when the
// radius is outside kRadiusRange diagonals of the H-net, when the centre is not finite, farther
// than kMaxCentreDistance diagonals from the H-net or within kMinCentreDistance of the diagonal
// of its surface (naming the face and parameters), and when a control point of the image is
// not finite.
DarbouxSkin MakeDarbouxSkin(const HNetPatchwork& hnet, const Inversion& inversion);

// The default inversion: centre half the H-net's bounding-box diagonal off its box's centre
// along the mean face normal, radius the distance from there to the box's centre (which maps
// to itself, so the skin stays about where and as large as the H-net).
Inversion DefaultInversion(const PolyMesh& mesh);
// The inversion about `centre` whose radius is its distance to the H-net's box centre.
Inversion InversionAbout(const PolyMesh& mesh, const Eigen::Vector3d& centre);

// The measures, taken in the H-net's unit frame (its box's centre at the origin, its diagonal
// 1), so that they are the same at every scale of the input.
struct DarbouxMeasures {
  // Tangent planes along the images of the inner edges (samples + 1 points each), degrees: the
  // skin's largest angle, the H-net's at the same points, and the largest difference.
  double max_tangent_angle_deg = 0.0;
  double hnet_max_tangent_angle_deg = 0.0;
  double max_tangent_angle_change_deg = 0.0;
  // The images of both ruling families (5 of each per patch, samples + 1 points each): the
  // largest distance of a point from the circle through three of them, and of the centre from
  // that circle (the image of a line is a circle through the centre), / the skin's diagonal.
  double max_circle_deviation = 0.0;
  double max_centre_off_circle = 0.0;
  int rulings = 0;
  // Gaussian curvature at samples × samples cell centres per patch, the skin's and the
  // H-net's at the same parameters. "flat": |K| diagonal² < 1e-9.
  int curvature_samples = 0;
  int skin_k_positive = 0, skin_k_negative = 0;
  int hnet_k_positive = 0, hnet_k_negative = 0;
  double skin_min_k = 0.0, skin_max_k = 0.0;  // × the skin's diagonal²
  // The largest difference between the skin's K and the one the inversion formula predicts
  // from the H-net's curvature, relative to max(|K'|, 1 / diagonal²).
  double max_curvature_formula_error = 0.0;
  // Patches with a non-positive weight (their Euclidean control points are not written).
  int patches_with_nonpositive_weights = 0;
  double hnet_diagonal = 0.0, skin_diagonal = 0.0;
  double centre_distance = 0.0;  // × the H-net's diagonal
};
DarbouxMeasures MeasureDarbouxSkin(const HNetPatchwork& hnet, const DarbouxSkin& skin,
                                   int samples = 8);

// The skin as JSON (docs/formats.md): the inversion, the H-net it came from, and per patch its
// homogeneous control points [X, Y, Z, W] (3 × 3, [i][j] with i along u), plus the Euclidean
// control points and weights where every weight is positive (a NURBS surface of degree 2 × 2
// with knots 0, 0, 0, 1, 1, 1).
nlohmann::json DarbouxSkinJson(const HNetPatchwork& hnet, const DarbouxSkin& skin);

// The skin sampled as a welded triangle mesh: the H-net's welded sample (SampleHNetSurface)
// with every vertex inverted (points of the skin exactly).
PolyMesh SampleDarbouxSkin(const HNetPatchwork& hnet, const DarbouxSkin& skin, int samples);

// A shaded picture with the faces coloured by the sign of the Gaussian curvature: each patch
// on a grid of up to samples × samples cells, fewer for many patches (about 20,000 triangles
// at most).
std::string DarbouxSkinSvg(const DarbouxSkin& skin, const std::string& title, int samples = 6);

}  // namespace gproj::nets
