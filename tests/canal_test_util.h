#pragma once
// The circular-strip input the canal tests share: a curve that bends in space, a first point and
// varying lengths.

#include <cmath>

#include "gproj/problems/circular/canal_surface.h"

namespace gproj {

inline circular::CircularStripInput BendingStripInput(int n = 8) {
  circular::CircularStripInput in;
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    in.curve.emplace_back(4.0 * s, 0.8 * std::sin(2.0 * s), 0.3 * s * s);
    in.lengths.push_back(1.0 + 0.2 * std::cos(3.0 * s));
  }
  in.first_point = Eigen::Vector3d(-0.3, 0.4, 1.2);
  return in;
}

}  // namespace gproj
