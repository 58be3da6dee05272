#pragma once
// The registrations of gproj's own problems, one function per problem (each in its family's
// folder); Registry::Builtin() adds them in this order.

#include "problems/run/registry.h"

namespace gproj {

ProblemSpec PlanarizeProblem();    // problems/planarize_problem.cc
ProblemSpec ANetProblem();         // problems/anet_problem.cc
ProblemSpec HNetProblem();         // problems/hnet_problem.cc
ProblemSpec FieldProblem();        // problems/field_problem.cc
ProblemSpec RemeshProblem();       // problems/remesh_problem.cc
ProblemSpec InvertProblem();       // problems/invert_problem.cc
ProblemSpec CyclidicProblem();     // problems/cyclidic_problem.cc
ProblemSpec CombescureProblem();   // problems/combescure_problem.cc
ProblemSpec BeamsProblem();        // problems/beams_problem.cc
ProblemSpec MRevolutionProblem();  // problems/mrevolution_problem.cc

}  // namespace gproj
