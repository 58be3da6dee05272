#include "gproj/constraints/edge_parallelism.h"

#include <cassert>

namespace gproj {

int EdgeParallelism::AddEdge(int a, int b, const Eigen::Vector3d& direction) {
  assert(direction.norm() > 0.0);
  return Add({a, b}, direction.normalized());
}

}  // namespace gproj
