// `gproj darboux` as a user runs it: grid → hnet → darboux on a generated hyperboloid net,
// the report's measures against the written files, and what it refuses.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"

namespace gproj {
namespace {

class DarbouxCommandTest : public CommandTest {
 protected:
  // A smooth H-net of a hyperboloid's jittered ruling grid (the A-net step and the rounds run).
  std::string HNet() {
    const CommandRun grid =
        Gproj("grid --surface hyperboloid --nu 9 --nv 9 --noise 0.02 -o " + Path("grid.obj"));
    EXPECT_EQ(grid.exit_code, 0) << grid.err;
    const CommandRun hnet = Gproj("hnet " + Path("grid.obj") + " -o " + Path("hnet.json"));
    EXPECT_EQ(hnet.exit_code, 0) << hnet.err << hnet.out;
    return Path("hnet.json");
  }
};

TEST_F(DarbouxCommandTest, HyperboloidHNetBecomesASmoothSkinWithBothCurvatureSigns) {
  const std::string hnet = HNet();
  const CommandRun run = Gproj(
      "darboux " + hnet + " --centre 0,0,0 --radius 1.2 -o " + Path("skin.json") + " --surface " +
      Path("skin.obj") + " --picture " + Path("skin.svg") + " --report " + Path("report.json"));
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const nlohmann::json report = Json("report.json");
  EXPECT_EQ(report["command"], "darboux");
  EXPECT_EQ(report["converged"], true);
  EXPECT_EQ(report["inversion"]["default"], false);
  EXPECT_EQ(report["inversion"]["radius"].get<double>(), 1.2);
  const nlohmann::json& m = report["measures"];
  EXPECT_LT(m["max_circle_deviation"].get<double>(), 1e-10);
  EXPECT_LT(m["max_centre_off_circle"].get<double>(), 1e-10);
  EXPECT_LT(m["max_tangent_angle_change_deg"].get<double>(), 1e-8);
  EXPECT_GT(m["k_positive_samples"].get<int>(), 0);
  EXPECT_GT(m["k_negative_samples"].get<int>(), 0);
  EXPECT_EQ(m["hnet_k_positive_samples"].get<int>(), 0);
  EXPECT_LT(m["max_curvature_formula_error"].get<double>(), 1e-8);
  EXPECT_NE(run.out.find("K > 0 at"), std::string::npos) << run.out;

  // The skin's JSON carries the inversion and the H-net; its patch corners are the inverted
  // H-net vertices.
  const nlohmann::json skin = Json("skin.json");
  const nlohmann::json h = Json("hnet.json");
  EXPECT_EQ(skin["hnet"]["faces"], h["faces"]);
  ASSERT_EQ(skin["patches"].size(), h["faces"].size());
  const auto inverted = [](const nlohmann::json& p) {
    const Eigen::Vector3d x(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    return Eigen::Vector3d(1.44 * x / x.squaredNorm());
  };
  for (std::size_t f = 0; f < skin["patches"].size(); ++f) {
    const nlohmann::json& corner = skin["patches"][f]["homogeneous_control_points"][0][0];
    const Eigen::Vector3d c(corner[0].get<double>() / corner[3].get<double>(),
                            corner[1].get<double>() / corner[3].get<double>(),
                            corner[2].get<double>() / corner[3].get<double>());
    const int v0 = h["faces"][f][0].get<int>();
    EXPECT_LT((c - inverted(h["vertices"][v0])).norm(), 1e-12);
  }
  // The sampled surface is welded: 81 vertices + 144 edges x 7 + 64 patches x 49.
  const PolyMesh surface = ReadMesh(Path("skin.obj"));
  EXPECT_EQ(surface.n_vertices(), 81u + 144u * 7u + 64u * 49u);
  EXPECT_NE(Slurp(dir_ / "skin.svg").find("K &gt; 0"), std::string::npos);
}

TEST_F(DarbouxCommandTest, DefaultInversionAndRefusals) {
  const std::string hnet = HNet();
  const CommandRun defaults =
      Gproj("darboux " + hnet + " -o " + Path("d.json") + " --report " + Path("d_report.json"));
  ASSERT_EQ(defaults.exit_code, 0) << defaults.err;
  EXPECT_EQ(Json("d_report.json")["inversion"]["default"], true);
  EXPECT_NE(defaults.out.find("(default)"), std::string::npos) << defaults.out;

  // A centre on the surface (an H-net vertex): exit 1, the option named, nothing written.
  const nlohmann::json h = Json("hnet.json");
  const nlohmann::json& v = h["vertices"][40];
  const std::string centre = std::to_string(v[0].get<double>()) + "," +
                             std::to_string(v[1].get<double>()) + "," +
                             std::to_string(v[2].get<double>());
  const CommandRun on = Gproj("darboux " + hnet + " --centre " + centre + " -o " + Path("on.json") +
                              " --surface " + Path("on.obj"));
  EXPECT_EQ(on.exit_code, 1);
  ExpectOneLineError(on, "--centre");
  EXPECT_NE(on.err.find("unbounded"), std::string::npos) << on.err;
  EXPECT_FALSE(Exists("on.json"));
  EXPECT_FALSE(Exists("on.obj"));

  // A broken H-net names the file and the key.
  nlohmann::json bad = h;
  bad["weights"][3][2] = 0.0;
  Write("bad.json", bad.dump());
  const CommandRun broken = Gproj("darboux " + Path("bad.json") + " -o " + Path("b.json"));
  EXPECT_EQ(broken.exit_code, 1);
  ExpectOneLineError(broken, "bad.json: weights[3][2] = 0");
  const CommandRun radius = Gproj("darboux " + hnet + " --radius -1 -o " + Path("r.json"));
  EXPECT_EQ(radius.exit_code, 1);
  ExpectOneLineError(radius, "--radius");
  EXPECT_FALSE(Exists("b.json"));

  // Patches that meet at kinks (all weights 1 on a hyperboloid: not an H-net) are warned about.
  nlohmann::json kinked = h;
  for (auto& w : kinked["weights"]) w = {1.0, 1.0, 1.0, 1.0};
  Write("kinked.json", kinked.dump());
  const CommandRun kinks = Gproj("darboux " + Path("kinked.json") + " -o " + Path("k.json"));
  EXPECT_EQ(kinks.exit_code, 0) << kinks.err;
  EXPECT_NE(kinks.err.find("not a smooth H-net"), std::string::npos) << kinks.err;
  // A centre so far off that rounding would show is refused.
  const CommandRun far = Gproj("darboux " + hnet + " --centre 1e8,0,0 -o " + Path("f.json"));
  EXPECT_EQ(far.exit_code, 1);
  ExpectOneLineError(far, "--centre: (1e+08, 0, 0) is");
}

}  // namespace
}  // namespace gproj
