#include "gproj/problems/run/registry.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/pq/pq_planarization.h"

namespace gproj {
namespace {

ProblemSpec Minimal(const std::string& name) {
  ProblemSpec spec;
  spec.name = name;
  spec.run = [](const RunInputs&, const nlohmann::json&, const RunContext&) { return RunResult(); };
  return spec;
}

TEST(RegistryTest, RefusesMalformedEntries) {
  Registry registry;
  registry.Add(Minimal("one"));
  EXPECT_THROW(registry.Add(Minimal("one")), std::invalid_argument);  // twice
  EXPECT_THROW(registry.Add(Minimal("Two")), std::invalid_argument);  // not an identifier
  EXPECT_THROW(registry.Add(Minimal("two-words")), std::invalid_argument);
  ProblemSpec no_run = Minimal("three");
  no_run.run = nullptr;
  EXPECT_THROW(registry.Add(no_run), std::invalid_argument);
  ProblemSpec twice = Minimal("four");
  OptionSpec option;
  option.name = "mesh";
  twice.options = {option};
  twice.inputs = {{"mesh", InputKind::kMesh, "", true}};  // an input and an option of one name
  EXPECT_THROW(registry.Add(twice), std::invalid_argument);
  ProblemSpec out_of_range = Minimal("five");
  option.name = "tolerance", option.default_value = -1.0, option.min = 0.0;
  out_of_range.options = {option};
  EXPECT_THROW(registry.Add(out_of_range), std::invalid_argument);
  ProblemSpec positional = Minimal("six");  // two optional positional inputs
  positional.inputs = {{"plan", InputKind::kMesh, "", false, true},
                       {"strip", InputKind::kText, "", false, true}};
  EXPECT_THROW(registry.Add(positional), std::invalid_argument);
  ProblemSpec generator = Minimal("seven");  // a generator without its mesh
  generator.generator = true;
  generator.outputs = {{"picture", OutputKind::kSvg, "", true}};
  EXPECT_THROW(registry.Add(generator), std::invalid_argument);
  generator.inputs = {{"mesh", InputKind::kMesh, "", true}};
  generator.outputs = {{"output", OutputKind::kMesh, "", true}};
  EXPECT_THROW(registry.Add(generator), std::invalid_argument);  // one with an input
  generator.inputs.clear();
  registry.Add(generator);
  EXPECT_EQ(registry.problems().size(), 2u);
  EXPECT_NE(registry.Find("one"), nullptr);
  EXPECT_EQ(registry.Find("two"), nullptr);
}

TEST(RegistryTest, TheBuiltinRegistryDescribesEveryProblem) {
  const Registry& registry = Registry::Builtin();
  ASSERT_FALSE(registry.problems().empty());
  const nlohmann::json schema = registry.SchemaJson();
  EXPECT_EQ(schema["version"], GprojVersion());
  ASSERT_EQ(schema["problems"].size(), registry.problems().size());
  for (const nlohmann::json& problem : schema["problems"]) {
    SCOPED_TRACE(problem["name"].get<std::string>());
    EXPECT_FALSE(problem["summary"].get<std::string>().empty());
    EXPECT_EQ(problem["inputs"].empty(),
              problem["generator"].get<bool>());  // only generators have none
    EXPECT_FALSE(problem["outputs"].empty());
    for (const nlohmann::json& option : problem["options"]) {
      SCOPED_TRACE(option["name"].get<std::string>());
      EXPECT_FALSE(option["doc"].get<std::string>().empty());
      if (option["type"] == "choice" && !option["default"].is_null()) {
        EXPECT_GE(option["choices"].size(), 2u);
        EXPECT_NE(std::find(option["choices"].begin(), option["choices"].end(), option["default"]),
                  option["choices"].end());
      }
    }
  }
}

TEST(RegistryTest, PlanarizeDefaultsAreTheProblemsOwn) {
  const ProblemSpec* spec = Registry::Builtin().Find("planarize");
  ASSERT_NE(spec, nullptr);
  const pq::PQPlanarizationOptions defaults;
  const auto default_of = [&](const std::string& name) {
    const OptionSpec* option = spec->FindOption(name);
    EXPECT_NE(option, nullptr) << name;
    return option ? option->default_value : nlohmann::json();
  };
  EXPECT_EQ(default_of("tolerance"), defaults.tolerance);
  EXPECT_EQ(default_of("closeness"), defaults.closeness_weight);
  EXPECT_EQ(default_of("max_iterations"), defaults.solver.max_iterations);
  EXPECT_EQ(default_of("fairness"), defaults.solver.fairness_weight);
  EXPECT_EQ(default_of("soft_decay"), defaults.solver.soft_weight_decay);
  EXPECT_EQ(default_of("monotone"), defaults.solver.monotone);
  EXPECT_EQ(default_of("min_angle"), defaults.panels.min_angle_deg);
  EXPECT_EQ(default_of("linear_solver"), "cholmod");
  EXPECT_EQ(default_of("solver"), "gp");
}

// The registry's run is the problem's own run: the same vertices to the last bit, options
// mapped by name (closeness, fairness, schedule, panel bounds, held vertices).
TEST(RegistryTest, PlanarizeThroughTheRegistryIsThePlanarizationItself) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 8;
  grid.noise = 0.05;
  const PolyMesh mesh = MakeQuadGrid(grid);
  pq::PQPlanarizationOptions options;
  options.closeness_weight = 30.0;
  options.solver.fairness_weight = 0.5;
  options.solver.max_iterations = 12;
  options.panels.min_angle_deg = 10.0;
  options.vertices.fixed = {0, 5};
  pq::PQPlanarization direct(mesh, options);
  const RunReport direct_report = direct.Run();

  RunInputs inputs;
  inputs.meshes["mesh"] = mesh;
  inputs.vertex_ids["fixed"] = {0, 5};
  std::vector<int> records;
  RunContext context;
  context.on_record = [&records](const RunRecord& r) {
    return records.push_back(r.iteration), true;
  };
  context.outputs = {"output", "face_values"};
  const RunResult result = RunProblem(
      *Registry::Builtin().Find("planarize"), inputs,
      {{"closeness", 30}, {"fairness", 0.5}, {"max_iterations", 12}, {"min_angle", 10}}, context);
  ASSERT_EQ(result.report.converged, direct_report.converged);
  EXPECT_EQ(result.report.iterations, direct_report.iterations);
  EXPECT_EQ(records.size(), result.report.history.size());
  const PolyMesh a = direct.Result(), &b = result.meshes.at("output");
  for (auto v : a.vertices()) EXPECT_EQ(a.point(v), b.point(v)) << v.idx();
  EXPECT_EQ(result.texts.count("face_values"), 1u);  // asked for
  EXPECT_EQ(result.texts.count("picture"), 0u);      // not asked for: not rendered
  EXPECT_EQ(result.facts["fixed_vertices"], 2);
}

TEST(RegistryTest, MessagesSpellOptionsForTheirFrontEnd) {
  const std::string text = "3 quads sit on their bound (`min_angle` 10); see `edge_length`";
  EXPECT_EQ(SpellOptions(text, true),
            "3 quads sit on their bound (--min-angle 10); see --edge-length");
  EXPECT_EQ(SpellOptions(text, false),
            "3 quads sit on their bound (min_angle 10); see edge_length");
  EXPECT_EQ(SpellOptions("a `Not an id` and an open `quote", true),
            "a `Not an id` and an open `quote");
}

TEST(RegistryTest, RunProblemRefusesBadOptionsAndMissingInputs) {
  const ProblemSpec& spec = *Registry::Builtin().Find("planarize");
  QuadGridOptions grid;
  grid.nu = grid.nv = 3;
  RunInputs inputs;
  EXPECT_THROW(RunProblem(spec, inputs, nullptr, {}), InputError);  // no mesh
  inputs.meshes["mesh"] = MakeQuadGrid(grid);
  EXPECT_THROW(RunProblem(spec, inputs, {{"tolerance", -1.0}}, {}), OptionError);
  EXPECT_THROW(RunProblem(spec, inputs, {{"tolerence", 1e-6}}, {}), OptionError);
  EXPECT_THROW(RunProblem(spec, inputs, {{"solver", "newton"}}, {}), OptionError);
  EXPECT_THROW(RunProblem(spec, inputs, {{"fix_boundary", true}, {"glide_boundary", true}}, {}),
               InputError);
}

}  // namespace
}  // namespace gproj
