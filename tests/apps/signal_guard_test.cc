#include <gtest/gtest.h>
#include <signal.h>

// METIS's own signal trap (libmetis): installs its SIGTERM and SIGABRT handlers, as it does for
// the length of every ordering call made by CHOLMOD.
extern "C" void gk_sigtrap(void);
extern "C" void gk_siguntrap(void);

namespace {

sighandler_t CurrentHandler(int signum) {
  struct sigaction current = {};
  EXPECT_EQ(sigaction(signum, nullptr, &current), 0);
  return current.sa_handler;
}

TEST(SignalGuard, MetisCannotTakeOverSigterm) {
  ASSERT_EQ(CurrentHandler(SIGTERM), SIG_DFL);
  const sighandler_t abort_before = CurrentHandler(SIGABRT);
  gk_sigtrap();
  EXPECT_EQ(CurrentHandler(SIGTERM), SIG_DFL);
  // SIGABRT stays with METIS (its out-of-memory path), and is restored afterwards.
  EXPECT_NE(CurrentHandler(SIGABRT), abort_before);
  gk_siguntrap();
  EXPECT_EQ(CurrentHandler(SIGTERM), SIG_DFL);
  EXPECT_EQ(CurrentHandler(SIGABRT), abort_before);
}

TEST(SignalGuardDeathTest, SigtermDuringMetisTerminates) {
  EXPECT_EXIT(
      {
        gk_sigtrap();
        raise(SIGTERM);
        _exit(0);  // reached only if the signal was swallowed
      },
      testing::KilledBySignal(SIGTERM), "");
}

TEST(SignalGuard, OtherSignalsKeepTheCLibrarySemantics) {
  const auto handler = [](int) {};
  const sighandler_t before = signal(SIGUSR1, handler);
  struct sigaction installed = {};
  ASSERT_EQ(sigaction(SIGUSR1, nullptr, &installed), 0);
  EXPECT_EQ(installed.sa_handler, static_cast<sighandler_t>(handler));
  EXPECT_TRUE(installed.sa_flags & SA_RESTART);
  EXPECT_TRUE(sigismember(&installed.sa_mask, SIGUSR1));
  EXPECT_EQ(signal(SIGUSR1, before), static_cast<sighandler_t>(handler));
}

}  // namespace
