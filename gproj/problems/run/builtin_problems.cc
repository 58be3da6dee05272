#include "gproj/problems/run/builtin_problems.h"

namespace gproj {

const Registry& Registry::Builtin() {
  static const Registry registry = [] {
    Registry r;
    r.Add(pq::PlanarizeSpec());
    r.Add(pq::DualSpec());
    r.Add(nets::ANetSpec());
    r.Add(nets::HNetSpec());
    r.Add(nets::DarbouxSpec());
    r.Add(remesh::FieldSpec());
    r.Add(remesh::RemeshSpec());
    r.Add(circular::InvertSpec());
    r.Add(circular::CyclidicSpec());
    r.Add(circular::CombescureSpec());
    r.Add(circular::BeamsSpec());
    r.Add(circular::MRevolutionSpec());
    r.Add(weingarten::WeingartenSpec());
    r.Add(marionette::MarionetteSpec());
    r.Add(circular::CanalSpec());
    r.Add(GridSpec());
    return r;
  }();
  return registry;
}

}  // namespace gproj
