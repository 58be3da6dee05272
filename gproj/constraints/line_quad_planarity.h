#pragma once
// Planarity of a quad whose vertices move on fixed lines p_j = o_j + t_j d_j (002 §4.1,
// Fig. 14: general projections), with an auxiliary unit normal per face as in 004 §3.2:
//   n_f · (p_{j+1} − p_j) = 0  (j = 0..3, indices mod 4),   n_f · n_f − 1 = 0.
// Bilinear in (n_f, t). Element items: {n_f (3), t_0, t_1, t_2, t_3 (1 each)}; five rows.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gproj/solver/term.h"

namespace gproj {

// The lines of a quad's vertices: p_j = o[j] + t_j d[j].
struct QuadLines {
  std::array<Eigen::Vector3d, 4> o, d;
};

struct LineQuadPlanarityResidual {
  template <typename T>
  void operator()(const QuadLines& lines, const T* n, const T* t0, const T* t1, const T* t2,
                  const T* t3, T* r) const {
    const T* t[4] = {t0, t1, t2, t3};
    for (int j = 0; j < 4; ++j) {
      const int k = (j + 1) % 4;
      T edge[3];
      for (int c = 0; c < 3; ++c)
        edge[c] = lines.o[k][c] + t[k][0] * lines.d[k][c] - lines.o[j][c] - t[j][0] * lines.d[j][c];
      r[j] = n[0] * edge[0] + n[1] * edge[1] + n[2] * edge[2];
    }
    r[4] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  }
};
using LineQuadPlanarityTerm = Term<QuadLines, LineQuadPlanarityResidual, 5, 3, 1, 1, 1, 1>;

// The term, declared quadratic (one coefficient model per quad: the lines differ).
class LineQuadPlanarity : public LineQuadPlanarityTerm {
 public:
  explicit LineQuadPlanarity(double weight = 1.0, std::string name = "planarity")
      : LineQuadPlanarityTerm(std::move(name), LineQuadPlanarityResidual{}, FamilyRole::kConstraint,
                              weight) {
    DeclareQuadratic();
  }

  // Adds one face: its normal item, the parameter items of its four vertices in cyclic order,
  // and their lines (origins o_j and directions d_j).
  int AddQuad(int normal, const std::array<int, 4>& t, const std::array<Eigen::Vector3d, 4>& o,
              const std::array<Eigen::Vector3d, 4>& d) {
    return Add({normal, t[0], t[1], t[2], t[3]}, QuadLines{o, d});
  }
};

}  // namespace gproj
