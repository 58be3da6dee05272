#include "gproj/problems/run/builtin_problems.h"

namespace gproj {

const Registry& Registry::Builtin() {
  static const Registry registry = [] {
    Registry r;
    r.Add(PlanarizeSpec());
    r.Add(ANetSpec());
    r.Add(HNetSpec());
    r.Add(FieldSpec());
    r.Add(RemeshSpec());
    r.Add(InvertSpec());
    r.Add(CyclidicSpec());
    r.Add(CombescureSpec());
    r.Add(BeamsSpec());
    r.Add(MRevolutionSpec());
    r.Add(WeingartenSpec());
    r.Add(MarionetteSpec());
    r.Add(CanalSpec());
    r.Add(GridSpec());
    return r;
  }();
  return registry;
}

}  // namespace gproj
