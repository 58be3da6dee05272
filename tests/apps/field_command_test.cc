// `gproj field` as a user runs it, on the shipped triangle mesh and generated ones.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "apps/command_test_util.h"

namespace gproj {
namespace {

class FieldCommandTest : public CommandTest {};

// The shipped monkey saddle: K < 0 on all of it, one singularity of index −½ at its flat point
// (004 Theorem 6), in the report with its position; the field as OBJ segments, two per vertex.
TEST_F(FieldCommandTest, MonkeySaddleHasOneSingularityOfIndexMinusHalf) {
  const CommandRun r = Gproj("field " + Data("monkey_saddle_tri.obj") + " -o " + Path("field.obj") +
                             " --picture " + Path("field.svg") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["command"], "field");
  EXPECT_GT(report["final"]["negative_area_fraction"].get<double>(), 0.99);
  ASSERT_EQ(report["singularities"].size(), 1u);
  const nlohmann::json& s = report["singularities"][0];
  EXPECT_EQ(s["index"].get<double>(), -0.5);
  EXPECT_LT(std::hypot(s["position"][0].get<double>(), s["position"][1].get<double>()), 0.2);
  const std::string obj = Slurp(dir_ / "field.obj");
  size_t segments = 0;
  for (size_t at = obj.find("\nl "); at != std::string::npos; at = obj.find("\nl ", at + 1))
    ++segments;
  EXPECT_EQ(segments, 2u * 961u);
  EXPECT_NE(Slurp(dir_ / "field.svg").find("<svg"), std::string::npos);
  EXPECT_NE(r.out.find("index -1/2: 1"), std::string::npos) << r.out;
  // Smoothed: the same singularity.
  const CommandRun smooth = Gproj("field " + Data("monkey_saddle_tri.obj") + " -o " +
                                  Path("smooth.obj") + " --smooth 1 --report " + Path("s.json"));
  ASSERT_EQ(smooth.exit_code, 0) << smooth.err;
  EXPECT_EQ(Json("s.json")["singularities"].size(), 1u);
  EXPECT_EQ(Json("s.json")["smoothing"].get<double>(), 1.0);
}

// A quad mesh, and asymptotic directions on a surface with K > 0 everywhere, are refused with
// the reason and nothing written.
TEST_F(FieldCommandTest, RefusesQuadsAndPositiveCurvatureForAsymptoticDirections) {
  ExpectOneLineError(Gproj("field " + Data("enneper_41x41.obj") + " -o " + Path("f.obj")),
                     "triangle mesh");
  {
    std::ofstream cap(Path("cap.obj"));
    const int n = 12;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double x = -0.5 + static_cast<double>(i) / n, y = -0.5 + static_cast<double>(j) / n;
        cap << "v " << x << ' ' << y << ' ' << std::sqrt(4.0 - x * x - y * y) << '\n';
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = i * (n + 1) + j + 1, b = a + n + 1;
        cap << "f " << a << ' ' << b << ' ' << b + 1 << "\nf " << a << ' ' << b + 1 << ' ' << a + 1
            << '\n';
      }
  }
  ExpectOneLineError(Gproj("field " + Path("cap.obj") + " -o " + Path("f.obj")), "K >= 0");
  EXPECT_FALSE(Exists("f.obj"));
  const CommandRun principal =
      Gproj("field " + Path("cap.obj") + " -o " + Path("f.obj") + " --directions principal");
  EXPECT_EQ(principal.exit_code, 0) << principal.err;
}

}  // namespace
}  // namespace gproj
