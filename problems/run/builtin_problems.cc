#include "problems/run/builtin_problems.h"

namespace gproj {

const Registry& Registry::Builtin() {
  static const Registry registry = [] {
    Registry r;
    r.Add(PlanarizeProblem());
    r.Add(ANetProblem());
    r.Add(HNetProblem());
    r.Add(FieldProblem());
    r.Add(RemeshProblem());
    r.Add(InvertProblem());
    r.Add(CyclidicProblem());
    r.Add(CombescureProblem());
    r.Add(BeamsProblem());
    r.Add(MRevolutionProblem());
    return r;
  }();
  return registry;
}

}  // namespace gproj
