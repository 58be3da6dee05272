// An H-net run stops where its callback returns false, in whichever stage that is: the A-net
// step, a round's vertex update, the joint solve of vertices and weights after the rounds, or the
// joint solve of a mesh that is not simply connected. No record reaches the callback after the
// stop, no later stage runs, and the report reads USER_ABORT.
#include <gtest/gtest.h>

#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/problems/nets/hnet.h"
#include "stop_test_util.h"

namespace gproj::nets {
namespace {

PolyMesh Grid(const std::string& surface, int n, double jitter = 0.0, uint32_t seed = 4) {
  ParametricGridOptions o;
  o.nu = o.nv = n;
  o.jitter = jitter;
  o.seed = seed;
  return MakeParametricGrid(AsymptoticSurface(surface), o);
}

RunInputs Inputs(const PolyMesh& mesh, const PolyMesh* reference = nullptr) {
  RunInputs inputs;
  inputs.meshes["mesh"] = mesh;
  inputs.sources["mesh"] = "mesh";
  if (reference) inputs.meshes["reference"] = *reference;
  return inputs;
}

// Where the records of an unstopped run come from: the A-net step's first, then each round's
// vertex update (its solver iterations, one record each).
struct Stages {
  int anet = 0;
  std::vector<int> rounds;  // records of each round, in order
  int FirstOfRound(size_t k) const {
    int first = anet + 1;
    for (size_t r = 0; r < k; ++r) first += rounds[r];
    return first;
  }
};

Stages StagesOf(const RunResult& unstopped, const StopCount& count) {
  Stages s;
  s.anet = static_cast<int>(unstopped.report.history.size());
  int total = s.anet;
  for (const nlohmann::json& r : unstopped.facts["rounds"]) {
    s.rounds.push_back(r["solver_iterations"].get<int>());
    total += s.rounds.back();
  }
  EXPECT_EQ(total, count.records) << "every iterate is a record";
  return s;
}

void ExpectUserAbort(const RunResult& r, const StopCount& count, int stop_at) {
  EXPECT_EQ(StatusOf(r.report), RunStatus::kUserAbort) << r.report.termination;
  EXPECT_FALSE(r.report.converged);
  EXPECT_FALSE(r.report.failed) << r.report.termination;
  EXPECT_EQ(count.records, stop_at) << "the run went on to the end instead";
  EXPECT_EQ(count.after_stop, 0);
}

TEST(HNetStopTest, AStopInTheANetStepEndsTheRunWithoutRounds) {
  const PolyMesh exact = Grid("hyperboloid", 11), mesh = Grid("hyperboloid", 11, 0.03);
  StopCount count;
  const RunResult unstopped = RunStoppedAt("hnet", Inputs(mesh, &exact), {}, 0, &count);
  ASSERT_GE(unstopped.report.history.size(), 3u);
  const RunResult r = RunStoppedAt("hnet", Inputs(mesh, &exact), {}, 2, &count);
  ExpectUserAbort(r, count, 2);
  EXPECT_TRUE(r.facts["rounds"].empty());
  EXPECT_EQ(r.texts.count("output"), 0u);  // no H-net: the rounds make it
}

// The rounds used to run to their end unasked (no record reached the callback), and the run
// ended "maximum number of rounds reached" or settled.
TEST(HNetStopTest, AStopInARoundsVertexUpdateEndsTheRunThere) {
  const PolyMesh exact = Grid("hypar", 15), mesh = Grid("hypar", 15, 0.1);
  StopCount count;
  const RunResult unstopped = RunStoppedAt("hnet", Inputs(mesh, &exact), {}, 0, &count);
  const Stages stages = StagesOf(unstopped, count);
  ASSERT_GE(stages.rounds.size(), 2u);
  ASSERT_GE(stages.rounds[0], 2) << "round 0's vertex update takes steps";
  const int stop_at = stages.FirstOfRound(0) + 1;  // its second step
  const RunResult r = RunStoppedAt("hnet", Inputs(mesh, &exact), {}, stop_at, &count);
  ExpectUserAbort(r, count, stop_at);
  EXPECT_NE(r.report.termination.find("round 0"), std::string::npos) << r.report.termination;
  ASSERT_EQ(r.facts["rounds"].size(), 1u);  // no later round
  EXPECT_EQ(r.facts["rounds"][0]["solver_iterations"], 2);
  EXPECT_EQ(r.report.iterations, stages.anet - 1 + 2);  // the A-net step's steps and two
  // The result is the last iterate, its measures those of the round.
  ASSERT_EQ(r.texts.count("output"), 1u);
  EXPECT_EQ(ValueOf(r.report.final, "max_star_planarity"),
            r.facts["rounds"][0]["max_star_planarity"].get<double>());
}

TEST(HNetStopTest, AStopInTheJointSolveAfterTheRoundsEndsTheRunThere) {
  // With Ceres' updates the rounds settle short of planar stars, and a joint solve follows.
  const PolyMesh exact = Grid("hypar", 7), mesh = Grid("hypar", 7, 0.03);
  const nlohmann::json options = {{"solver", "ceres"}};
  StopCount count;
  const RunResult unstopped = RunStoppedAt("hnet", Inputs(mesh, &exact), options, 0, &count);
  const Stages stages = StagesOf(unstopped, count);
  ASSERT_NE(unstopped.report.termination.find("joint solve"), std::string::npos)
      << unstopped.report.termination;
  const size_t joint = stages.rounds.size() - 1;
  ASSERT_GE(stages.rounds[joint], 3);
  // A stop in a round first, then in the joint solve.
  RunResult r = RunStoppedAt("hnet", Inputs(mesh, &exact), options, stages.FirstOfRound(1), &count);
  ExpectUserAbort(r, count, stages.FirstOfRound(1));
  EXPECT_EQ(r.facts["rounds"].size(), 2u);
  const int stop_at = stages.FirstOfRound(joint) + 2;
  r = RunStoppedAt("hnet", Inputs(mesh, &exact), options, stop_at, &count);
  ExpectUserAbort(r, count, stop_at);
  EXPECT_NE(r.report.termination.find("joint solve"), std::string::npos) << r.report.termination;
  ASSERT_EQ(r.facts["rounds"].size(), joint + 1);
  EXPECT_EQ(r.facts["rounds"][joint]["solver_iterations"], 3);
  EXPECT_EQ(r.texts.count("output"), 1u);
}

// The shipped demo of issue 32: a jittered Enneper net with its reference; its rounds and joint
// solve took seconds after a stop and ended "maximum number of rounds reached".
TEST(HNetStopTest, TheShippedEnneperNetStopsInItsJointSolve) {
  const std::string data = std::string(GPROJ_SOURCE_DIR) + "/examples/data/";
  const PolyMesh mesh = ReadMesh(data + "enneper_41x41_jitter3.obj");
  const PolyMesh reference = ReadMesh(data + "enneper_41x41.obj");
  StopCount count;
  const RunResult unstopped = RunStoppedAt("hnet", Inputs(mesh, &reference), {}, 0, &count);
  const Stages stages = StagesOf(unstopped, count);
  ASSERT_NE(unstopped.report.termination.find("joint solve"), std::string::npos)
      << unstopped.report.termination;
  const size_t joint = stages.rounds.size() - 1;
  ASSERT_GE(stages.rounds[joint], 1);
  const int stop_at = stages.FirstOfRound(joint);
  const RunResult r = RunStoppedAt("hnet", Inputs(mesh, &reference), {}, stop_at, &count);
  ExpectUserAbort(r, count, stop_at);
  EXPECT_NE(r.report.termination.find("joint solve"), std::string::npos) << r.report.termination;
  EXPECT_EQ(r.facts["rounds"].size(), joint + 1);
}

TEST(HNetStopTest, AStopInTheJointSolveOfAMeshNotSimplyConnectedEndsTheRunThere) {
  // A 12 × 12 grid without an inner face: an annulus; round 0 propagates, round 1 solves
  // jointly.
  const PolyMesh grid = Grid("hyperboloid", 13, 0.05);
  PolyMesh annulus;
  for (auto v : grid.vertices()) annulus.add_vertex(grid.point(v));
  int k = 0;
  for (auto f : grid.faces()) {
    if (k++ == 5 * 12 + 5) continue;
    std::vector<PolyMesh::VertexHandle> vs;
    for (auto fv : grid.fv_range(f)) vs.push_back(PolyMesh::VertexHandle(fv.idx()));
    annulus.add_face(vs);
  }
  const nlohmann::json options = {{"allow_not_simply_connected", true}};
  StopCount count;
  const RunResult unstopped = RunStoppedAt("hnet", Inputs(annulus), options, 0, &count);
  const Stages stages = StagesOf(unstopped, count);
  ASSERT_EQ(stages.rounds.size(), 2u) << unstopped.report.termination;
  ASSERT_GE(stages.rounds[1], 2);
  const int stop_at = stages.FirstOfRound(1) + 1;
  const RunResult r = RunStoppedAt("hnet", Inputs(annulus), options, stop_at, &count);
  ExpectUserAbort(r, count, stop_at);
  ASSERT_EQ(r.facts["rounds"].size(), 2u);
  EXPECT_EQ(r.facts["rounds"][1]["solver_iterations"], 2);
}

// Watching a run does not change it: with a callback that never stops, the same H-net to the
// last bit as without one.
TEST(HNetStopTest, ACallbackThatNeverStopsChangesNothing) {
  const PolyMesh exact = Grid("hypar", 9), mesh = Grid("hypar", 9, 0.1);
  for (SolverKind solver : {SolverKind::kGuidedProjection, SolverKind::kCeres}) {
    HNetOptions options;
    options.solver = solver;
    HNet quiet(mesh, &exact, options), watched(mesh, &exact, options);
    const HNetSummary a = quiet.Run();
    int records = 0;
    const HNetSummary b = watched.Run([&records](const RunRecord&) { return ++records, true; });
    EXPECT_GT(records, static_cast<int>(b.report.history.size()));  // the rounds' records too
    EXPECT_EQ(a.report.termination, b.report.termination);
    EXPECT_EQ(a.report.iterations, b.report.iterations);
    ASSERT_EQ(a.rounds.size(), b.rounds.size());
    for (auto v : quiet.mesh().vertices())
      EXPECT_EQ(quiet.mesh().point(v), watched.mesh().point(v)) << v.idx();
    EXPECT_EQ(quiet.weights(), watched.weights());
  }
}

}  // namespace
}  // namespace gproj::nets
