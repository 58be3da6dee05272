// Careless options on every command: NaN, infinity, negative and out-of-range values are
// refused before any work with one line naming the option (exit 1, nothing written), and sizes
// that cannot fit are refused up front instead of aborting later.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "apps/command_test_util.h"

namespace gproj {
namespace {

class OptionValidationTest : public CommandTest {};

struct BadOption {
  std::string args;    // after "gproj", output to out.*
  std::string option;  // named in the message
  std::string rule;    // the rule broken, as the message says it
};

TEST_F(OptionValidationTest, NonFiniteAndOutOfRangeValuesAreRefusedNamingTheOption) {
  const std::string grid = Data("noisy_grid_21x21.obj"), spline = Data("freeform_10x10.json");
  const std::string weingarten = "weingarten " + spline + " -o " + Path("out.json");
  const std::vector<BadOption> cases = {
      {"planarize " + grid + " -o " + Path("out.obj") + " --epsilon nan", "--epsilon",
       "nan is not a finite number"},
      {"planarize " + grid + " -o " + Path("out.obj") + " --closeness inf", "--closeness",
       "inf is not a finite number"},
      {"planarize " + grid + " -o " + Path("out.obj") + " --soft-decay 2", "--soft-decay",
       "2 is not in [1e-12, 1]"},
      {weingarten + " --max-iterations -1", "--max-iterations", "-1 is not in [1, 100000]"},
      {weingarten + " --epsilon 0", "--epsilon", "0 is not > 0"},
      {weingarten + " --tolerance 0", "--tolerance", "0 is not > 0"},
      {"planarize " + grid + " -o " + Path("out.obj") + " --closeness ''", "--closeness",
       "an empty value is not allowed"},
      {"planarize " + grid + " -o " + Path("out.obj") + " --max-iterations ''", "--max-iterations",
       "an empty value is not allowed"},
      {"planarize " + grid + " -o " + Path("out.obj") + " --report ''", "--report",
       "an empty value is not allowed"},
      {weingarten + " --alignment nan", "--alignment", "nan is not a finite number"},
      {weingarten + " --boundary nan", "--boundary", "nan is not a finite number"},
      {weingarten + " --soft-start nan", "--soft-start", "nan is not a finite number"},
      {weingarten + " --molds -5", "--molds", "-5 is not in [0, 1000000]"},
      {weingarten + " --samples 0 0", "--samples", "0 is not in [5, 100000]"},
      {"marionette " + Data("marionette_plan_21x21.obj") + " -o " + Path("out.obj") +
           " --max-iterations -5",
       "--max-iterations", "-5 is not in [1, 100000]"},
      {"marionette " + Data("marionette_plan_21x21.obj") + " -o " + Path("out.obj") +
           " --tolerance -1",
       "--tolerance", "-1 is not > 0"},
      {"marionette " + Data("marionette_plan_21x21.obj") + " -o " + Path("out.obj") +
           " --row 0,nan --column 0,1",
       "--row", "nan is not a finite number"},
      {"combescure " + Data("revolution_13x17.obj") + " -o " + Path("out.obj") + " --row-scale 0",
       "--row-scale", "0 is not > 0"},
      {"grid -o " + Path("out.obj") + " --noise nan", "--noise", "nan is not a finite number"},
      {"canal " + Data("canal_curve.txt") + " -o " + Path("out.obj") +
           " --first-point 0,0,nan --length 1",
       "--first-point", "nan is not a finite number"},
  };
  for (const BadOption& c : cases) {
    const CommandRun r = Gproj(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.option + ": " + c.rule), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_FALSE(Exists("out.obj"));
  EXPECT_FALSE(Exists("out.json"));
}

// Weights so large that the solve overflows: exit 4 with one line, and none of the outputs
// (the report included) is written.
TEST_F(OptionValidationTest, NumericalFailureWritesNothing) {
  const CommandRun r =
      Gproj("planarize " + Data("noisy_grid_21x21.obj") + " -o " + Path("out.obj") +
            " --fairness 1e300 --report " + Path("r.json") + " --picture " + Path("p.svg"));
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("nothing written"), std::string::npos) << r.err;
  EXPECT_FALSE(Exists("out.obj"));
  EXPECT_FALSE(Exists("r.json"));
  EXPECT_FALSE(Exists("p.svg"));

  // Finite inputs whose result overflows the measures: exit 4 as well, not a success or a
  // degenerate mesh written with exit 3.
  std::string huge = "1e308";
  for (int k = 0; k < 20; ++k) huge += "," + std::to_string(0.1 * (k + 1));
  std::string lengths = "1e300";
  for (int k = 0; k < 15; ++k) lengths += ",1e300";
  for (const std::string& args :
       {"marionette " + Data("marionette_plan_21x21.obj") + " --row " + huge + " --column " + huge +
            " -o " + Path("out.obj") + " --report " + Path("r.json"),
        "combescure " + Data("revolution_13x17.obj") + " --row-lengths " + lengths + " -o " +
            Path("out.obj") + " --report " + Path("r.json")}) {
    const CommandRun o = Gproj(args);
    EXPECT_EQ(o.exit_code, 4) << args << "\n" << o.err;
    EXPECT_NE(o.err.find("is not finite"), std::string::npos) << o.err;
    EXPECT_FALSE(Exists("out.obj")) << args;
    EXPECT_FALSE(Exists("r.json")) << args;
  }
  const std::string zeros = "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0";
  ExpectOneLineError(Gproj("combescure " + Data("revolution_13x17.obj") + " --row-lengths " +
                           zeros + " -o " + Path("out.obj")),
                     "row length 0 is not finite and non-zero");
  EXPECT_FALSE(Exists("out.obj"));
}

// An output over an input or over another output is refused before any work, naming both.
TEST_F(OptionValidationTest, OutputsMustBeDistinctFilesAndNotInputs) {
  const std::string input = Path("in.obj");
  std::filesystem::copy_file(Data("noisy_grid_21x21.obj"), input);
  const std::string before = Slurp(input);
  const std::vector<BadOption> cases = {
      {"planarize " + input + " -o " + Path("p.obj") + " --report " + Path("p.obj"), "--report",
       "--output and --report are the same file"},
      {"planarize " + input + " -o " + input, "--output", "is the input file"},
      {"anet " + input + " -o " + Path("a.obj") + " --reference " + Path("a.obj"), "--output",
       "is the --reference file"},
      {"weingarten " + Data("freeform_10x10.json") + " -o " + Path("w.json") + " --curvature " +
           Path("w.json"),
       "--curvature", "--output and --curvature are the same file"},
      {"canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2 -o " +
           Path("c.obj") + " --strip " + Path("c.obj"),
       "--strip", "--output and --strip are the same file"},
      {"canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2 -o " +
           Path("c.obj") + " --normal 0,0,0",
       "--normal", "--normal must not be zero"},
  };
  for (const BadOption& c : cases) {
    const CommandRun r = Gproj(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.rule), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.option), std::string::npos) << c.args << "\n" << r.err;
  }
  // The same file spelt two ways, relative to the working directory.
  const CommandRun spelt = Gproj("planarize in.obj -o p.obj --report ./p.obj", /*in_dir=*/true);
  EXPECT_EQ(spelt.exit_code, 1) << spelt.err;
  EXPECT_NE(spelt.err.find("--output and --report are the same file"), std::string::npos)
      << spelt.err;
  EXPECT_EQ(Slurp(input), before);
  for (const char* name : {"p.obj", "a.obj", "w.json", "c.obj"}) EXPECT_FALSE(Exists(name)) << name;
}

TEST_F(OptionValidationTest, SizesThatCannotFitAreRefusedBeforeAllocating) {
  const CommandRun grid = Gproj("grid -o " + Path("g.obj") + " --nu 100000 --nv 100000");
  EXPECT_EQ(grid.exit_code, 1) << grid.err;
  EXPECT_NE(grid.err.find("--nu 100000 --nv 100000 needs about"), std::string::npos) << grid.err;
  EXPECT_FALSE(Exists("g.obj"));
  const CommandRun samples = Gproj("weingarten " + Data("freeform_10x10.json") + " -o " +
                                   Path("w.json") + " --samples 100000 100000");
  EXPECT_EQ(samples.exit_code, 1) << samples.err;
  EXPECT_NE(samples.err.find("100000 x 100000 samples at the finest, at bi-degree (4, 4) needs "
                             "about 6.5e+05 GB of memory"),
            std::string::npos)
      << samples.err;
  EXPECT_FALSE(Exists("w.json"));
}

}  // namespace
}  // namespace gproj
