#pragma once
// Running the gproj binary as a user does, in a fresh directory per test: exit code, stdout and
// stderr, the files written.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace gproj {

struct CommandRun {
  int exit_code = -1;
  std::string out, err;
};

class CommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::path(::testing::TempDir()) /
        ("gproj_cli_" +
         std::string(::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
         std::to_string(getpid()));  // two suites running at once (e.g. two checkouts) never
                                     // share a directory
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::string Data(const std::string& name) {
    return std::string(GPROJ_SOURCE_DIR) + "/examples/data/" + name;
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  bool Exists(const std::string& name) const { return std::filesystem::exists(dir_ / name); }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return Path(name);
  }
  static std::string Slurp(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  nlohmann::json Json(const std::string& name) const {
    return nlohmann::json::parse(Slurp(dir_ / name));
  }
  // Runs `gproj ARGS`, capturing stdout and stderr; with in_dir, from the test's directory (for
  // relative paths).
  CommandRun Gproj(const std::string& args, bool in_dir = false) {
    const std::string cmd = (in_dir ? "cd '" + dir_.string() + "' && " : std::string()) +
                            std::string(GPROJ_BINARY) + " " + args + " >" + Path("stdout") + " 2>" +
                            Path("stderr");
    const int status = std::system(cmd.c_str());
    CommandRun r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = Slurp(dir_ / "stdout");
    r.err = Slurp(dir_ / "stderr");
    return r;
  }
  // Expects exit 1 with a one-line error containing `part`.
  static void ExpectOneLineError(const CommandRun& r, const std::string& part) {
    EXPECT_EQ(r.exit_code, 1) << r.err << r.out;
    EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }

  std::filesystem::path dir_;
};

}  // namespace gproj
