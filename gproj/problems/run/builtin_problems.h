#pragma once
// The registrations of gproj's own problems, one function per problem (each in its family's
// folder and namespace); Registry::Builtin() adds them in this order.

#include "gproj/problems/run/registry.h"

namespace gproj {

namespace pq {
ProblemSpec PlanarizeSpec();  // gproj/problems/pq/planarize_problem.cc
ProblemSpec DualSpec();       // gproj/problems/pq/dual_problem.cc
}  // namespace pq

namespace nets {
ProblemSpec ANetSpec();     // gproj/problems/nets/anet_problem.cc
ProblemSpec HNetSpec();     // gproj/problems/nets/hnet_problem.cc
ProblemSpec DarbouxSpec();  // gproj/problems/nets/darboux_problem.cc
}  // namespace nets

namespace remesh {
ProblemSpec FieldSpec();   // gproj/problems/remesh/field_problem.cc
ProblemSpec RemeshSpec();  // gproj/problems/remesh/remesh_problem.cc
}  // namespace remesh

namespace circular {
ProblemSpec InvertSpec();       // gproj/problems/circular/invert_problem.cc
ProblemSpec CyclidicSpec();     // gproj/problems/circular/cyclidic_problem.cc
ProblemSpec CombescureSpec();   // gproj/problems/circular/combescure_problem.cc
ProblemSpec BeamsSpec();        // gproj/problems/circular/beams_problem.cc
ProblemSpec MRevolutionSpec();  // gproj/problems/circular/mrevolution_problem.cc
ProblemSpec CanalSpec();        // gproj/problems/circular/canal_problem.cc
}  // namespace circular

namespace weingarten {
ProblemSpec WeingartenSpec();  // gproj/problems/weingarten/weingarten_problem.cc
}  // namespace weingarten

namespace marionette {
ProblemSpec MarionetteSpec();  // gproj/problems/marionette/marionette_problem.cc
}  // namespace marionette

ProblemSpec GridSpec();  // gproj/problems/mesh/grid_problem.cc

}  // namespace gproj
