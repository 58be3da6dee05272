#pragma once
// The registrations of gproj's own problems, one function per problem (each in its family's
// folder); Registry::Builtin() adds them in this order.

#include "problems/run/registry.h"

namespace gproj {

ProblemSpec PlanarizeSpec();    // problems/planarize_problem.cc
ProblemSpec ANetSpec();         // problems/anet_problem.cc
ProblemSpec HNetSpec();         // problems/hnet_problem.cc
ProblemSpec FieldSpec();        // problems/field_problem.cc
ProblemSpec RemeshSpec();       // problems/remesh_problem.cc
ProblemSpec InvertSpec();       // problems/invert_problem.cc
ProblemSpec CyclidicSpec();     // problems/cyclidic_problem.cc
ProblemSpec CombescureSpec();   // problems/combescure_problem.cc
ProblemSpec BeamsSpec();        // problems/beams_problem.cc
ProblemSpec MRevolutionSpec();  // problems/mrevolution_problem.cc
ProblemSpec WeingartenSpec();   // problems/weingarten_problem.cc
ProblemSpec MarionetteSpec();   // problems/marionette_problem.cc
ProblemSpec CanalSpec();        // problems/canal_problem.cc
ProblemSpec GridSpec();         // problems/grid_problem.cc

}  // namespace gproj
