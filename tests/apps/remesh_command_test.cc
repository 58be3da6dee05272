// `gproj remesh` as a user runs it, on the shipped triangle mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "apps/command_test_util.h"
#include "geometry/mesh_io.h"

namespace gproj {
namespace {

class RemeshCommandTest : public CommandTest {};

// The shipped monkey saddle remeshed along its asymptotic directions: quads only, one vertex of
// valence 6 at the flat point (004 Theorem 6), every other inner vertex of valence 4; the
// report, the field and the picture written.
TEST_F(RemeshCommandTest, MonkeySaddleAlongItsAsymptoticDirections) {
  const CommandRun r =
      Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("quads.obj") +
            " --edge-length 0.15 --field " + Path("field.obj") + " --picture " + Path("quads.svg") +
            " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["command"], "remesh");
  ASSERT_EQ(report["singularities"].size(), 1u);
  EXPECT_EQ(report["singularities"][0]["index"].get<double>(), -0.5);
  EXPECT_EQ(report["inner_valences"]["6"].get<int>(), 1);
  EXPECT_EQ(report["inner_valences"].size(), 2u) << report["inner_valences"].dump();
  EXPECT_EQ(report["final"]["odd_inner_vertices"].get<double>(), 0.0);
  EXPECT_GT(report["final"]["area_covered"].get<double>(), 0.75);
  EXPECT_LT(report["final"]["mean_alignment_deg"].get<double>(), 3.0);
  const PolyMesh quads = ReadMesh(Path("quads.obj"));
  EXPECT_EQ(static_cast<double>(quads.n_faces()), report["final"]["quads"].get<double>());
  for (auto f : quads.faces()) EXPECT_EQ(quads.valence(f), 4u);
  EXPECT_NE(Slurp(dir_ / "quads.svg").find("<circle"), std::string::npos);
  EXPECT_NE(Slurp(dir_ / "field.obj").find("\nl "), std::string::npos);
  EXPECT_NE(r.out.find("inner valences: 4:"), std::string::npos) << r.out;
}

// Quads, a missing file and a bad option value are refused in one line, nothing written.
TEST_F(RemeshCommandTest, RefusesWhatItCannotRemesh) {
  ExpectOneLineError(Gproj("remesh " + Data("enneper_41x41.obj") + " -o " + Path("q.obj")),
                     "triangle mesh");
  EXPECT_FALSE(Exists("q.obj"));
  ExpectOneLineError(Gproj("remesh " + Path("missing.obj") + " -o " + Path("q.obj")),
                     "missing.obj");
  ExpectOneLineError(Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("q.obj") +
                           " --edge-length -1"),
                     "--edge-length");
  ExpectOneLineError(Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("q.obj") +
                           " --edge-length 100"),
                     "no quad");
  EXPECT_FALSE(Exists("q.obj"));
}

}  // namespace
}  // namespace gproj
