#pragma once
// Edge parallelism between two meshes of one connectivity (000 eq. 3, §2.4: Combescure
// transformations): for every edge, e × (b − a) = 0, with e the unit direction of the edge in
// the fixed reference mesh and a, b the edge's vertices in the unknown mesh. Three rows per
// edge (rank two), linear in the unknowns.
//
// EdgeVector prescribes a whole edge vector, b − a − d = 0 (three rows): the lengths given along
// two crossing polylines in the Combescure construction (000 §2.5).
// Element items for both: {a, b}, dimension 3 each. Both are terms declared quadratic, the
// direction or vector stored beside each element.

#include <Eigen/Core>
#include <string>

#include "gproj/solver/term.h"

namespace gproj {

struct EdgeParallelismResidual {
  // e: the unit direction of the reference edge.
  template <typename T>
  void operator()(const Eigen::Vector3d& e, const T* a, const T* b, T* r) const {
    const T d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    r[0] = e[1] * d[2] - e[2] * d[1];
    r[1] = e[2] * d[0] - e[0] * d[2];
    r[2] = e[0] * d[1] - e[1] * d[0];
  }
};
using EdgeParallelismTerm = Term<Eigen::Vector3d, EdgeParallelismResidual, 3, 3, 3>;

class EdgeParallelism : public EdgeParallelismTerm {
 public:
  explicit EdgeParallelism(double weight = 1.0, std::string name = "edge parallelism")
      : EdgeParallelismTerm(std::move(name), EdgeParallelismResidual{}, FamilyRole::kConstraint,
                            weight) {
    DeclareQuadratic();
  }

  // `direction` need not be unit; it is normalised (and must be non-zero).
  int AddEdge(int a, int b, const Eigen::Vector3d& direction);
};

struct EdgeVectorResidual {
  template <typename T>
  void operator()(const Eigen::Vector3d& v, const T* a, const T* b, T* r) const {
    for (int c = 0; c < 3; ++c) r[c] = b[c] - a[c] - v[c];
  }
};
using EdgeVectorTerm = Term<Eigen::Vector3d, EdgeVectorResidual, 3, 3, 3>;

class EdgeVector : public EdgeVectorTerm {
 public:
  explicit EdgeVector(double weight = 1.0, std::string name = "edge vector")
      : EdgeVectorTerm(std::move(name), EdgeVectorResidual{}, FamilyRole::kConstraint, weight) {
    DeclareQuadratic();
  }

  int AddEdge(int a, int b, const Eigen::Vector3d& vector) { return Add({a, b}, vector); }
};

}  // namespace gproj
