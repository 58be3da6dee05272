// The generated command line agrees with the registry: every option of every problem is a flag
// with the schema's default, `gproj schema` is the registry, unknown commands are refused, and a
// planarize run writes what the library returns.
#include <gtest/gtest.h>

#include "command_test_util.h"
#include "gproj/problems/run/registry.h"

namespace gproj {
namespace {

class ProblemCommandTest : public CommandTest {};

std::string FlagOf(std::string name) {
  for (char& c : name)
    if (c == '_') c = '-';
  return "--" + name;
}

TEST_F(ProblemCommandTest, EveryOptionIsAFlagWithTheSchemasDefault) {
  for (const ProblemSpec& spec : Registry::Builtin().problems()) {
    const CommandRun help = Gproj(spec.name + " --help");
    ASSERT_EQ(help.exit_code, 0) << spec.name;
    for (const OptionSpec& option : spec.options) {
      SCOPED_TRACE(spec.name + " " + option.name);
      // The flag itself, not one it begins ("--fairness" in "--fairness-order").
      size_t at = help.out.find(FlagOf(option.name));
      while (at != std::string::npos &&
             std::string(" ,\n").find(help.out[at + FlagOf(option.name).size()]) ==
                 std::string::npos)
        at = help.out.find(FlagOf(option.name), at + 1);
      ASSERT_NE(at, std::string::npos) << help.out;
      const std::string line = help.out.substr(at, help.out.find('\n', at) - at);
      if (option.type != OptionType::kBool && !option.default_value.is_null()) {
        EXPECT_NE(line.find("=" + OptionText(option.default_value)), std::string::npos) << line;
      }
      // The schema's range, as the registry states it, in the flag's entry (which CLI11 wraps
      // onto the next line after a long flag).
      const std::string entry = help.out.substr(at, help.out.find("\n  -", at) - at);
      if (!option.RangeText().empty()) {
        EXPECT_NE(entry.find(option.RangeText()), std::string::npos) << entry;
      }
      if (!option.negation.empty()) {
        EXPECT_NE(help.out.find(FlagOf(option.negation)), std::string::npos);
      }
    }
    for (const OutputSpec& output : spec.outputs)
      EXPECT_NE(help.out.find(FlagOf(output.name)), std::string::npos) << output.name;
  }
}

TEST_F(ProblemCommandTest, SchemaCommandPrintsTheRegistry) {
  const CommandRun r = Gproj("schema");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out), Registry::Builtin().SchemaJson());
  const CommandRun written = Gproj("schema -o " + Path("schema.json"));
  ASSERT_EQ(written.exit_code, 0) << written.err;
  EXPECT_EQ(Json("schema.json"), Registry::Builtin().SchemaJson());
  const CommandRun missing = Gproj("schema -o " + Path("no/such/dir/schema.json"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("does not exist"), std::string::npos) << missing.err;
}

// docs/reference is generated from the registry; a change to a problem's schema must come with
// its regenerated page (gproj schema --markdown docs/reference).
TEST_F(ProblemCommandTest, TheCheckedInReferencePagesAreCurrent) {
  const CommandRun r = Gproj("schema --markdown " + Path(""));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const ProblemSpec& spec : Registry::Builtin().problems()) {
    const std::string page = Slurp(dir_ / (spec.name + ".md"));
    EXPECT_EQ(page, ReferenceMarkdown(spec));
    EXPECT_EQ(Slurp(std::string(GPROJ_SOURCE_DIR) + "/docs/reference/" + spec.name + ".md"), page)
        << "docs/reference/" << spec.name
        << ".md is out of date: run gproj schema --markdown docs/reference";
    for (const OptionSpec& option : spec.options)
      EXPECT_NE(page.find("`" + option.name + "`"), std::string::npos) << option.name;
  }
}

TEST_F(ProblemCommandTest, VersionAndUnknownCommands) {
  const CommandRun version = Gproj("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, std::string("gproj ") + GprojVersion() + "\n");
  for (const char* args : {"server --help", "planarise x.obj -o y.obj", "web"}) {
    const CommandRun r = Gproj(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_NE(r.err.find("unknown command"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("planarize"), std::string::npos) << r.err;  // lists the known ones
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST_F(ProblemCommandTest, TheReportsOptionsAreTheSchemasNames) {
  const CommandRun r =
      Gproj("planarize " + Data("noisy_grid_21x21.obj") + " -o " + Path("out.obj") +
            " --closeness 50 --plain-steps --edge-length 0.01,5 --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json options = Json("r.json")["options"];
  const ProblemSpec& spec = *Registry::Builtin().Find("planarize");
  EXPECT_EQ(options, CompleteOptions(
                         spec.options,
                         {{"closeness", 50.0}, {"monotone", false}, {"edge_length", {0.01, 5.0}}}));
}

TEST_F(ProblemCommandTest, OptionErrorsNameTheFlag) {
  const std::string grid = Data("noisy_grid_21x21.obj");
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"--fairness-order 4", "--fairness-order: 4 is not in [2, 3]"},
           {"--edge-length 1,2,3", "--edge-length: expects 2 numbers (MIN,MAX), not 3"},
           {"--solver newton", "--solver: 'newton' is not one of gp, ceres"},
           {"--max-iterations 2.5", "--max-iterations: 2.5 is not an integer"}}) {
    const CommandRun r = Gproj("planarize " + grid + " -o " + Path("out.obj") + " " + args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(Exists("out.obj"));
  }
}

// A rule that joins options names them as flags, never as the library's identifiers.
TEST_F(ProblemCommandTest, RunErrorsNameOptionsAsFlags) {
  const CommandRun r = Gproj("invert " + Data("revolution_13x17.obj") + " -o " + Path("out.obj"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "gproj invert: give --centre (x, y, z) or --m-revolution (4 concyclic points)\n");
  EXPECT_FALSE(Exists("out.obj"));
}

}  // namespace
}  // namespace gproj
