// Ctrl-C on the command line: the first SIGINT stops the run where it is (an iterate, or
// between the steps of Weingarten's paneling), the result and report at the stop are written
// and the command exits 130; a second SIGINT ends the process at once, writing nothing.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <vector>

#include "tests/apps/command_test_util.h"

extern char** environ;

namespace gproj {
namespace {

struct Child {
  pid_t pid = -1;
  int out = -1;  // the read end of its stdout
  std::string seen;
};

// Starts `gproj args...` with stdout on a pipe and stderr in `err`.
Child Start(const std::vector<std::string>& args, const std::string& err) {
  int fds[2];
  EXPECT_EQ(pipe(fds), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> all = {GPROJ_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  Child child;
  EXPECT_EQ(posix_spawn(&child.pid, GPROJ_BINARY, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  child.out = fds[0];
  return child;
}

// Reads the child's stdout until it contains `text` (true) or ends (false).
bool ReadUntil(Child* child, const std::string& text) {
  char buffer[4096];
  while (child->seen.find(text) == std::string::npos) {
    const ssize_t n = read(child->out, buffer, sizeof(buffer));
    if (n <= 0) return false;
    child->seen.append(buffer, n);
  }
  return true;
}

// Waits for the child, draining its stdout; the wait status.
int Wait(Child* child) {
  ReadUntil(child, std::string(1, '\0'));  // to the end
  close(child->out);
  int status = 0;
  waitpid(child->pid, &status, 0);
  return status;
}

class InterruptTest : public CommandTest {
 protected:
  // A tight planarisation of a noisy grid (many iterations), read up to its first step.
  Child StartPlanarization() {
    const CommandRun r =
        Gproj("grid --nu 101 --nv 101 --surface hypar --noise 0.08 -o " + Path("grid.obj"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    Child child = Start({"planarize", Path("grid.obj"), "-o", Path("out.obj"), "--report",
                         Path("report.json"), "--tolerance", "1e-14", "--max-iterations", "500"},
                        Path("stderr"));
    // The header and the start's record, then one step.
    EXPECT_TRUE(ReadUntil(&child, "\n    1 ")) << child.seen;
    return child;
  }
};

TEST_F(InterruptTest, CtrlCStopsAPlanarizationAtItsNextIterateAndWritesTheResult) {
  Child child = StartPlanarization();
  kill(child.pid, SIGINT);
  const int status = Wait(&child);
  ASSERT_TRUE(WIFEXITED(status)) << child.seen;
  EXPECT_EQ(WEXITSTATUS(status), 130) << child.seen << Slurp(Path("stderr"));
  EXPECT_NE(Slurp(Path("stderr")).find("stopped by Ctrl-C"), std::string::npos);
  ASSERT_TRUE(Exists("out.obj") && Exists("report.json"));
  const nlohmann::json report = Json("report.json");
  EXPECT_EQ(report["status"], "USER_ABORT") << report["termination"];
  EXPECT_FALSE(report["converged"].get<bool>());
  EXPECT_LT(report["iterations"].get<int>(), 500);
}

TEST_F(InterruptTest, ASecondCtrlCEndsTheProcessAtOnceWritingNothing) {
  Child child = StartPlanarization();
  kill(child.pid, SIGINT);
  kill(child.pid, SIGINT);
  const int status = Wait(&child);
  // The first may already have ended the run; then the command exits 130 as above.
  if (WIFEXITED(status)) {
    EXPECT_EQ(WEXITSTATUS(status), 130);
  } else {
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), SIGINT);
    EXPECT_FALSE(Exists("out.obj"));
    EXPECT_FALSE(Exists("report.json"));
  }
}

TEST_F(InterruptTest, CtrlCDuringWeingartenPanelingStopsThePaneling) {
  Child child = Start({"weingarten", Data("freeform_10x10.json"), "-o", Path("out.json"),
                       "--report", Path("report.json"), "--max-iterations", "2", "--panels",
                       "10,10", "--panel-tolerance", "0.01,10"},
                      Path("stderr"));
  ASSERT_TRUE(ReadUntil(&child, "paneling the input")) << child.seen;
  kill(child.pid, SIGINT);
  const int status = Wait(&child);
  ASSERT_TRUE(WIFEXITED(status)) << child.seen;
  EXPECT_EQ(WEXITSTATUS(status), 130) << child.seen << Slurp(Path("stderr"));
  ASSERT_TRUE(Exists("report.json"));
  const nlohmann::json report = Json("report.json");
  EXPECT_EQ(report["status"], "USER_ABORT");
  EXPECT_NE(report["termination"].get<std::string>().find("paneling"), std::string::npos)
      << report["termination"];
  EXPECT_FALSE(report.contains("panels"));
}

}  // namespace
}  // namespace gproj
