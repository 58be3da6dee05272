// Every run ends with one of a fixed set of statuses, the first word of its termination, and
// converged agrees with it (CONVERGENCE, DIRECT, COMPLETED) whatever the solver said.
#include <gtest/gtest.h>

#include "gproj/problems/run/guided_problem.h"

namespace gproj {
namespace {

RunReport Report(const std::string& termination, bool converged, bool failed = false,
                 SolverKind solver = SolverKind::kGuidedProjection, std::string method = "") {
  RunReport r;
  r.termination = termination;
  r.converged = converged;
  r.failed = failed;
  r.solver = solver;
  r.method = std::move(method);
  ConcludeStatus(&r);
  return r;
}

TEST(RunStatusTest, CeresStopsByTheCallbackAreUserAborts) {
  const RunReport abort = Report("ceres-bfgs USER_FAILURE: User callback returned SOLVER_ABORT.",
                                 false, false, SolverKind::kCeres);
  EXPECT_EQ(StatusOf(abort), RunStatus::kUserAbort) << abort.termination;
  const RunReport stop =
      Report("ceres USER_SUCCESS: User callback returned SOLVER_TERMINATE_SUCCESSFULLY.", false);
  EXPECT_EQ(StatusOf(stop), RunStatus::kUserAbort) << stop.termination;
  EXPECT_FALSE(stop.converged);
  // The tolerance check stops Ceres the same way when the tolerance is met.
  const RunReport met =
      Report("ceres USER_SUCCESS: User callback returned SOLVER_TERMINATE_SUCCESSFULLY.", true);
  EXPECT_EQ(StatusOf(met), RunStatus::kConvergence) << met.termination;
  EXPECT_NE(met.termination.find("USER_SUCCESS"), std::string::npos);  // the solver's words kept
}

TEST(RunStatusTest, ConvergedAgreesWithTheStatus) {
  EXPECT_EQ(StatusOf(Report("constructed directly (mirror images)", true, false,
                            SolverKind::kDirect, "closed form")),
            RunStatus::kDirect);
  // A solver's own NO_CONVERGENCE beside a met tolerance, and CONVERGENCE beside a missed one.
  const RunReport met = Report("Termination: NO_CONVERGENCE", true, false, SolverKind::kCeres);
  EXPECT_EQ(StatusOf(met), RunStatus::kConvergence) << met.termination;
  const RunReport short_of =
      Report("ceres-bfgs CONVERGENCE: function tolerance", false, false, SolverKind::kCeres);
  EXPECT_EQ(StatusOf(short_of), RunStatus::kStalled) << short_of.termination;
  const RunReport rounds = Report("maximum number of rounds reached", false);
  EXPECT_EQ(StatusOf(rounds), RunStatus::kNoConvergence) << rounds.termination;
  // A failure is never converged, whatever it said before.
  const RunReport failed = Report("CONVERGENCE: step tolerance met", true, true);
  EXPECT_EQ(StatusOf(failed), RunStatus::kFailure);
  EXPECT_FALSE(failed.converged);
  // Statuses already in place are kept as they are.
  const RunReport completed = Report("COMPLETED: no tolerance was asked", true);
  EXPECT_EQ(completed.termination, "COMPLETED: no tolerance was asked");
  EXPECT_STREQ(RunStatusName(StatusOf(completed)), "COMPLETED");
}

}  // namespace
}  // namespace gproj
