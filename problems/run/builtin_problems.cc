#include "problems/run/builtin_problems.h"

namespace gproj {

const Registry& Registry::Builtin() {
  static const Registry registry = [] {
    Registry r;
    r.Add(PlanarizeProblem());
    r.Add(ANetProblem());
    r.Add(FieldProblem());
    r.Add(RemeshProblem());
    return r;
  }();
  return registry;
}

}  // namespace gproj
