#include "gproj/problems/nets/darboux.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/problems/nets/hnet.h"
#include "tests/input_error_test_util.h"

namespace gproj::nets {
namespace {

// The H-net of a hyperboloid's ruling grid: weights propagated exactly (tangent planes join to
// ~1e-8 deg); with `unit_weights` all weights 1 instead (the patches meet at kinks).
HNetPatchwork Hyperboloid(int n, bool unit_weights = false) {
  ParametricGridOptions o;
  o.nu = o.nv = n;
  HNetPatchwork hnet;
  hnet.mesh = MakeParametricGrid(AsymptoticSurface("hyperboloid"), o);
  const std::vector<int> colour = TwoColourVertices(hnet.mesh);
  const ShapeParameters shape = PropagateShapeParameters(hnet.mesh, colour, 0);
  for (auto f : hnet.mesh.faces())
    hnet.weights.push_back(
        CornerWeights(hnet.mesh, colour, f, unit_weights ? 1.0 : shape.w[f.idx()]));
  return hnet;
}

Inversion At(const Eigen::Vector3d& centre, double radius) {
  Inversion inversion;
  inversion.centre = centre;
  inversion.radius = radius;
  return inversion;
}

TEST(DarbouxTest, BilinearPatchIsTheHNetPatch) {
  const HNetPatchwork hnet = Hyperboloid(6);
  for (auto f : hnet.mesh.faces()) {
    const RationalBezierPatch patch = HNetPatch(hnet.mesh, f, hnet.weights[f.idx()]);
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.2, 0.9}) {
        Eigen::Vector3d point, normal;
        EvaluatePatch(hnet.mesh, f, hnet.weights[f.idx()], u, v, &point, &normal);
        const PatchJet jet = EvaluateJet(patch, u, v);
        EXPECT_LT((jet.point - point).norm(), 1e-13);
        EXPECT_LT((jet.du.cross(jet.dv).normalized() - normal).norm(), 1e-12);
      }
  }
}

// The biquadratic image is exact: every parameter maps to the inverted point.
TEST(DarbouxTest, ImagePatchIsTheInvertedPatchExactly) {
  const HNetPatchwork hnet = Hyperboloid(6);
  const Inversion inversion = At({0.2, -0.4, 3.0}, 2.5);
  const DarbouxSkin skin = MakeDarbouxSkin(hnet, inversion);
  ASSERT_EQ(skin.patches.size(), hnet.mesh.n_faces());
  for (std::size_t f = 0; f < skin.patches.size(); ++f) {
    EXPECT_EQ(skin.patches[f].degree_u, 2);
    for (double u : {0.0, 0.15, 0.5, 0.85, 1.0})
      for (double v : {0.0, 0.4, 1.0}) {
        const Eigen::Vector3d expected = inversion.Apply(EvaluatePoint(skin.hnet_patches[f], u, v));
        EXPECT_LT((EvaluatePoint(skin.patches[f], u, v) - expected).norm(),
                  1e-13 * expected.norm());
      }
  }
  // The inversion is an involution.
  const Eigen::Vector3d p(0.7, 0.1, -0.3);
  EXPECT_LT((inversion.Apply(inversion.Apply(p)) - p).norm(), 1e-14);
}

TEST(DarbouxTest, RulingsBecomeCirclesThroughTheCentre) {
  const HNetPatchwork hnet = Hyperboloid(7);
  const DarbouxSkin skin = MakeDarbouxSkin(hnet, At({0.5, 0.3, 2.0}, 1.7));
  const DarbouxMeasures m = MeasureDarbouxSkin(hnet, skin, 8);
  EXPECT_EQ(m.rulings, 10 * static_cast<int>(hnet.mesh.n_faces()));
  EXPECT_LT(m.max_circle_deviation, 1e-10);
  EXPECT_LT(m.max_centre_off_circle, 1e-10);
  // Independently: seven points of one image ruling on the circle fitted to all of them, and
  // the H-net's ruling itself straight (not a circle: the measure can fail).
  std::vector<Eigen::Vector3d> image, line;
  for (int k = 0; k <= 6; ++k) {
    image.push_back(EvaluatePoint(skin.patches[5], 0.35, k / 6.0));
    line.push_back(EvaluatePoint(skin.hnet_patches[5], 0.35, k / 6.0));
  }
  const Circle circle = FitCircle(image.data(), static_cast<int>(image.size()));
  for (const Eigen::Vector3d& p : image) EXPECT_LT(DistanceToCircle(p, circle), 1e-10);
  EXPECT_LT(DistanceToCircle(skin.inversion.centre, circle), 1e-10);
  for (const Eigen::Vector3d& p : line)
    EXPECT_LT((p - line[0]).cross(line[6] - line[0]).norm(), 1e-12);
}

// Conformal: the skin's patches meet at the H-net's angles, whether these are ~0 (an exact
// H-net) or not (unit weights, kinks > 0.01 deg).
TEST(DarbouxTest, TangentPlaneAnglesAreTheHNets) {
  for (bool unit_weights : {false, true}) {
    const HNetPatchwork hnet = Hyperboloid(8, unit_weights);
    const DarbouxSkin skin = MakeDarbouxSkin(hnet, At({0.1, 0.2, 1.5}, 1.2));
    const DarbouxMeasures m = MeasureDarbouxSkin(hnet, skin, 8);
    EXPECT_NEAR(m.hnet_max_tangent_angle_deg, MaxTangentPlaneAngle(hnet.mesh, hnet.weights, 8),
                1e-9);
    EXPECT_LT(m.max_tangent_angle_change_deg, 1e-8) << "unit weights " << unit_weights;
    if (unit_weights)
      EXPECT_GT(m.max_tangent_angle_deg, 0.01);
    else
      EXPECT_LT(m.max_tangent_angle_deg, 1e-6);
  }
}

// A centre on the hyperboloid's axis, inside its waist: K > 0 near the waist, K < 0 farther
// out, on one skin; K agrees with the inversion's formula from the H-net's curvature.
TEST(DarbouxTest, OneSkinHasBothSignsOfGaussianCurvature) {
  const HNetPatchwork hnet = Hyperboloid(9);
  const DarbouxSkin skin = MakeDarbouxSkin(hnet, At({0.0, 0.0, 0.0}, 1.0));
  const DarbouxMeasures m = MeasureDarbouxSkin(hnet, skin, 6);
  EXPECT_EQ(m.hnet_k_negative, m.curvature_samples);
  EXPECT_GT(m.skin_k_positive, 0);
  EXPECT_GT(m.skin_k_negative, 0);
  EXPECT_GT(m.skin_max_k, 0.0);
  EXPECT_LT(m.skin_min_k, 0.0);
  EXPECT_LT(m.max_curvature_formula_error, 1e-8);
  // A far centre keeps K < 0 everywhere.
  const DarbouxSkin far = MakeDarbouxSkin(hnet, At({0.0, 0.0, 100.0}, 100.0));
  const DarbouxMeasures mf = MeasureDarbouxSkin(hnet, far, 6);
  EXPECT_EQ(mf.skin_k_positive, 0);
  EXPECT_EQ(mf.skin_k_negative, mf.curvature_samples);
}

TEST(DarbouxTest, RefusesACentreOnTheSurface) {
  const HNetPatchwork hnet = Hyperboloid(6);
  const auto f = hnet.mesh.face_handle(7);
  Eigen::Vector3d on, normal;
  EvaluatePatch(hnet.mesh, f, hnet.weights[7], 0.3, 0.6, &on, &normal);
  const std::string message =
      InputErrorOf([&] { MakeDarbouxSkin(hnet, At(on + 1e-6 * normal, 1.0)); });
  EXPECT_NE(message.find("`centre`"), std::string::npos) << message;
  EXPECT_NE(message.find("patch 7"), std::string::npos) << message;
  EXPECT_NE(message.find("unbounded"), std::string::npos) << message;
  // A hundredth of the diagonal off the surface is accepted, and the skin is then much larger
  // than the H-net but finite.
  const DarbouxSkin skin = MakeDarbouxSkin(hnet, At(on + 0.05 * normal, 1.0));
  const DarbouxMeasures m = MeasureDarbouxSkin(hnet, skin, 4);
  EXPECT_GT(m.skin_diagonal, 5.0 * m.hnet_diagonal);
  EXPECT_TRUE(std::isfinite(m.skin_diagonal));
  EXPECT_NE(InputErrorOf([&] { MakeDarbouxSkin(hnet, At(on, 0.0)); }).find("`radius`"),
            std::string::npos);
}

TEST(DarbouxTest, JsonReadsBackAndGivesTheSamePoints) {
  const HNetPatchwork hnet = Hyperboloid(5);
  const HNetPatchwork read = ParseHNetJson(HNetJson(hnet.mesh, hnet.weights).dump(), "h.json");
  ASSERT_EQ(read.mesh.n_faces(), hnet.mesh.n_faces());
  for (std::size_t f = 0; f < hnet.weights.size(); ++f)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(read.weights[f][k], hnet.weights[f][k]);
  // Faces listed from another corner: the weights follow their vertices.
  nlohmann::json rotated = HNetJson(hnet.mesh, hnet.weights);
  for (auto& face : rotated["faces"]) face = {face[1], face[2], face[3], face[0]};
  for (auto& w : rotated["weights"]) w = {w[1], w[2], w[3], w[0]};
  const HNetPatchwork turned = ParseHNetJson(rotated.dump(), "h.json");
  for (auto f : hnet.mesh.faces()) {
    Eigen::Vector3d a, b, n;
    EvaluatePatch(hnet.mesh, f, hnet.weights[f.idx()], 0.5, 0.5, &a, &n);
    EvaluatePatch(turned.mesh, f, turned.weights[f.idx()], 0.5, 0.5, &b, &n);
    EXPECT_LT((a - b).norm(), 1e-14);
  }

  // The skin's JSON: Euclidean control points and weights evaluate to the patch.
  const DarbouxSkin skin = MakeDarbouxSkin(hnet, At({0.3, 0.1, 2.5}, 2.0));
  const nlohmann::json json = DarbouxSkinJson(hnet, skin);
  ASSERT_EQ(json["patches"].size(), skin.patches.size());
  EXPECT_EQ(json["inversion"]["radius"].get<double>(), 2.0);
  const nlohmann::json& patch = json["patches"][3];
  ASSERT_TRUE(patch.contains("weights"));
  RationalBezierPatch from_json(2, 2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double w = patch["weights"][i][j].get<double>();
      const auto& p = patch["control_points"][i][j];
      from_json.At(i, j) << w * p[0].get<double>(), w * p[1].get<double>(), w * p[2].get<double>(),
          w;
    }
  EXPECT_LT((EvaluatePoint(from_json, 0.3, 0.8) - EvaluatePoint(skin.patches[3], 0.3, 0.8)).norm(),
            1e-13);
}

TEST(DarbouxTest, HNetJsonErrorsNameTheKeyAndIndex) {
  const HNetPatchwork hnet = Hyperboloid(4);
  const nlohmann::json good = HNetJson(hnet.mesh, hnet.weights);
  const auto error = [](const nlohmann::json& j) {
    return InputErrorOf([&] { ParseHNetJson(j.dump(), "h.json"); });
  };
  nlohmann::json j = good;
  j.erase("weights");
  EXPECT_EQ(error(j), "h.json: missing key \"weights\"");
  j = good;
  j["weights"][2][1] = -0.5;
  EXPECT_NE(error(j).find("h.json: weights[2][1] = -0.5"), std::string::npos) << error(j);
  j = good;
  j["weights"].erase(0);
  EXPECT_NE(error(j).find("\"weights\" has 8 rows for 9 faces"), std::string::npos) << error(j);
  j = good;
  j["faces"][4] = {0, 1, 2};
  EXPECT_NE(error(j).find("faces[4]: expected four vertex ids"), std::string::npos);
  j = good;
  j["faces"][1][3] = 99;
  EXPECT_NE(error(j).find("faces[1][3]: expected an integer vertex id in [0, 16)"),
            std::string::npos);
  j = good;
  j["vertices"][3][2] = "x";
  EXPECT_NE(error(j).find("vertices[3][2] is not a number"), std::string::npos);
  EXPECT_NE(
      InputErrorOf([] { ParseHNetJson("{\"vertices\": [", "h.json"); }).find("not valid JSON"),
      std::string::npos);
  // A NUL byte after a valid H-net (a JSON reader stops there) is refused.
  EXPECT_NE(InputErrorOf([&] {
              ParseHNetJson(good.dump() + std::string(1, '\0') + "x", "h.json");
            }).find("h.json: a NUL byte at byte " + std::to_string(good.dump().size())),
            std::string::npos);
}

// The measures are taken in the H-net's unit frame: the same at every scale and position.
TEST(DarbouxTest, MeasuresAreTheSameAtEveryScale) {
  const HNetPatchwork hnet = Hyperboloid(7);
  const DarbouxMeasures base =
      MeasureDarbouxSkin(hnet, MakeDarbouxSkin(hnet, At({0.0, 0.0, 0.0}, 1.2)), 6);
  ASSERT_GT(base.skin_k_positive, 0);
  for (double scale : {1e-150, 1e-20, 1e20, 1e150}) {
    HNetPatchwork scaled = hnet;
    const Eigen::Vector3d shift(3.0, -2.0, 1.0);
    for (auto v : scaled.mesh.vertices())
      scaled.mesh.set_point(v, (hnet.mesh.point(v) + PolyMesh::Point(3.0, -2.0, 1.0)) * scale);
    const DarbouxSkin skin = MakeDarbouxSkin(scaled, At(shift * scale, 1.2 * scale));
    const DarbouxMeasures m = MeasureDarbouxSkin(scaled, skin, 6);
    EXPECT_EQ(m.skin_k_positive, base.skin_k_positive) << scale;
    EXPECT_EQ(m.skin_k_negative, base.skin_k_negative) << scale;
    EXPECT_NEAR(m.skin_max_k, base.skin_max_k, 1e-8 * std::abs(base.skin_max_k)) << scale;
    EXPECT_LT(m.max_circle_deviation, 1e-10) << scale;
    EXPECT_NEAR(m.skin_diagonal / scale, base.skin_diagonal, 1e-10 * base.skin_diagonal);
  }
  // A radius or a centre the precision cannot take is refused, naming the option.
  EXPECT_NE(InputErrorOf([&] {
              MakeDarbouxSkin(hnet, At({0, 0, 0}, 1e300));
            }).find("`radius`"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] {
              MakeDarbouxSkin(hnet, At({0, 0, 0}, 1e-300));
            }).find("`radius`"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] {
              MakeDarbouxSkin(hnet, At({1e12, 0, 0}, 1.0));
            }).find("`centre`: (1e+12, 0, 0) is"),
            std::string::npos);
}

// The welded sample: as many vertices as the H-net's, each on the skin (its corners at the
// inverted vertices).
TEST(DarbouxTest, SampledSkinIsWeldedAndOnTheSkin) {
  const HNetPatchwork hnet = Hyperboloid(5);
  const DarbouxSkin skin = MakeDarbouxSkin(hnet, At({0.3, 0.1, 2.5}, 2.0));
  const PolyMesh sampled = SampleDarbouxSkin(hnet, skin, 4);
  const PolyMesh flat = SampleHNetSurface(hnet.mesh, hnet.weights, 4);
  ASSERT_EQ(sampled.n_vertices(), flat.n_vertices());
  ASSERT_EQ(sampled.n_faces(), flat.n_faces());
  for (auto v : hnet.mesh.vertices()) {
    const auto& p = hnet.mesh.point(v);
    const auto& q = sampled.point(PolyMesh::VertexHandle(v.idx()));
    const Eigen::Vector3d expected = skin.inversion.Apply({p[0], p[1], p[2]});
    EXPECT_LT((Eigen::Vector3d(q[0], q[1], q[2]) - expected).norm(), 1e-13);
  }
  const std::string svg = DarbouxSkinSvg(skin, "skin");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
}

}  // namespace
}  // namespace gproj::nets
