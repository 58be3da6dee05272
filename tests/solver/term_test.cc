#include "gproj/solver/term.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "constraint_test_util.h"
#include "gproj/constraints/quad_planarity.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"
#include "test_problems.h"

namespace gproj {
namespace {

std::vector<double> RandomVector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = u(rng);
  return x;
}

// Pattern of element e as rows × local booleans.
std::vector<bool> Pattern(const ConstraintFamily& family, int e, const std::vector<double>& x) {
  const int n = static_cast<int>(x.size());
  std::unique_ptr<bool[]> touches(new bool[family.rows_per_element() * n]);
  family.RowPattern(e, x.data(), n, touches.get());
  return std::vector<bool>(touches.get(), touches.get() + family.rows_per_element() * n);
}

// A term with data, Eigen maps, sqrt and a branch: r0 = (‖a − b‖ − l)·s, r1 = a_z − t or b_z − t.
struct Spring {
  double length = 1.0;
  double target = 0.0;
  bool on_a = true;
};
struct SpringResidual {
  template <typename T>
  void operator()(const Spring& d, const T* a, const T* b, const T* s, T* r) const {
    using Vec = Eigen::Matrix<T, 3, 1>;
    const Vec diff = Eigen::Map<const Vec>(a) - Eigen::Map<const Vec>(b);
    r[0] = (diff.norm() - d.length) * s[0];
    r[1] = d.on_a ? a[2] - d.target : b[2] - d.target;
  }
};

TEST(TermTest, JacobianMatchesFiniteDifferencesWithData) {
  Problem problem;
  problem.layout().AddBlock("points", 2, 3);  // items 0, 1
  problem.layout().AddBlock("length", 1, 1);  // item 2
  auto* springs = problem.AddTerm<Spring, 2, 3, 3, 1>("springs", SpringResidual{});
  springs->Add({0, 1, 2}, Spring{1.5, 0.3, true});
  springs->Add({0, 1, 2}, Spring{0.5, -0.2, false});
  for (int e = 0; e < 2; ++e)
    for (unsigned seed = 1; seed <= 4; ++seed)
      ExpectGradientMatchesFiniteDifferences(*springs, e, RandomVector(7, seed));
}

// Eigen expressions (cross, dot, squaredNorm) and std functions inside a term: the volume of
// the tetrahedron (a, b, c, d) and the angle at a, on any scalar type.
struct TetraResidual {
  template <typename T>
  void operator()(const T* a, const T* b, const T* c, const T* d, T* r) const {
    using std::atan2;
    using Vec = Eigen::Matrix<T, 3, 1>;
    const Vec pa = Eigen::Map<const Vec>(a), ab = Eigen::Map<const Vec>(b) - pa,
              ac = Eigen::Map<const Vec>(c) - pa, ad = Eigen::Map<const Vec>(d) - pa;
    r[0] = ab.cross(ac).dot(ad);
    r[1] = atan2(ab.cross(ac).norm(), ab.dot(ac));
    r[2] = ad.squaredNorm();
  }
};

TEST(TermTest, EigenExpressionsDifferentiateAndGiveTheirSparsity) {
  Problem problem;
  problem.layout().AddBlock("corners", 4, 3);
  auto* tetra = problem.AddTerm<3, 3, 3, 3, 3>("tetra", TetraResidual{});
  tetra->Add({0, 1, 2, 3});
  for (unsigned seed = 1; seed <= 3; ++seed)
    ExpectGradientMatchesFiniteDifferences(*tetra, 0, RandomVector(12, seed), 1e-6, 1e-6);
  const std::vector<bool> pattern = Pattern(*tetra, 0, RandomVector(12, 4));
  for (int l = 0; l < 12; ++l) {
    EXPECT_TRUE(pattern[l]) << "the volume uses every vertex, local " << l;
    EXPECT_EQ(pattern[12 + l], l < 9) << "the angle at a ignores d, local " << l;
    EXPECT_EQ(pattern[24 + l], l < 3 || l >= 9) << "|ad|² uses a and d, local " << l;
  }
}

TEST(TermTest, SparsityIsDerivedPerRowAndFollowsData) {
  Problem problem;
  problem.layout().AddBlock("points", 2, 3);
  problem.layout().AddBlock("length", 1, 1);
  auto* springs = problem.AddTerm<Spring, 2, 3, 3, 1>("springs", SpringResidual{});
  springs->Add({0, 1, 2}, Spring{1.0, 0.0, true});
  springs->Add({0, 1, 2}, Spring{1.0, 0.0, false});
  const std::vector<double> x = RandomVector(7, 9);
  const std::vector<bool> p0 = Pattern(*springs, 0, x), p1 = Pattern(*springs, 1, x);
  for (int l = 0; l < 7; ++l) EXPECT_TRUE(p0[l]) << "row 0 uses every scalar, local " << l;
  for (int l = 0; l < 7; ++l) {
    EXPECT_EQ(p0[7 + l], l == 2) << "row 1 of element 0 uses a_z only, local " << l;
    EXPECT_EQ(p1[7 + l], l == 5) << "row 1 of element 1 uses b_z only, local " << l;
  }
}

TEST(TermTest, QuadraticCoefficientsGiveTheJetsValuesAndPattern) {
  QuadPlanarity hand;  // declared quadratic: evaluated from coefficients after Prepare
  hand.AddQuad(0, 1, 2, 3, 4);
  hand.Prepare();
  QuadPlanarityTerm automatic("planarity", QuadPlanarityResidual{});
  automatic.Add({0, 1, 2, 3, 4});
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const std::vector<double> x = RandomVector(15, seed);
    std::vector<double> phi_h(5), jac_h(75), phi_a(5), jac_a(75);
    hand.EvaluateElement(0, x.data(), phi_h.data(), jac_h.data());
    automatic.EvaluateElement(0, x.data(), phi_a.data(), jac_a.data());
    for (int r = 0; r < 5; ++r) EXPECT_NEAR(phi_h[r], phi_a[r], 1e-15);
    for (int k = 0; k < 75; ++k) EXPECT_NEAR(jac_h[k], jac_a[k], 1e-15) << "entry " << k;
    // Structural sparsity: row j touches the normal and vertices j, j+1; the unit row only n.
    const std::vector<bool> pattern = Pattern(automatic, 0, x);
    for (int row = 0; row < 5; ++row)
      for (int l = 0; l < 15; ++l) {
        const int vertex = (l - 3) / 3;
        const bool expected = l < 3 || (row < 4 && (vertex == row || vertex == (row + 1) % 4));
        EXPECT_EQ(pattern[row * 15 + l], expected) << "row " << row << " local " << l;
      }
  }
}

// MakeCircleProblem (test_problems.h) written with terms: points pulled onto the unit circle,
// anchored (soft) and smoothed along the chain (fairness).
Problem MakeCircleTermProblem(int n, double anchor_weight) {
  Problem problem;
  const int block = problem.layout().AddBlock("points", n, 2);
  problem.ResizeToLayout();
  auto* circle = problem.AddTerm<1, 2>(
      "on_circle", [](const auto* p, auto* r) { r[0] = p[0] * p[0] + p[1] * p[1] - 1.0; });
  auto* anchor = problem.AddTerm<Eigen::Vector2d, 2, 2>(
      "anchor",
      [](const Eigen::Vector2d& p0, const auto* p, auto* r) {
        r[0] = p[0] - p0[0];
        r[1] = p[1] - p0[1];
      },
      FamilyRole::kSoft, anchor_weight);
  auto* smooth = problem.AddTerm<2, 2, 2, 2>(
      "smooth",
      [](const auto* a, const auto* b, const auto* c, auto* r) {
        for (int k = 0; k < 2; ++k) r[k] = a[k] - 2.0 * b[k] + c[k];
      },
      FamilyRole::kFairness);
  for (int i = 0; i < n; ++i) {
    const double t = 0.3 * i, radius = 1.0 + 0.2 * std::sin(3.0 * i);
    problem.x().segment<2>(problem.layout().Index(block, i, 0)) << radius * std::cos(t),
        radius * std::sin(t);
  }
  const VariableLayout& layout = problem.layout();
  circle->AddElements(IndexRange(n),
                      [&](int i) { return std::array<int, 1>{layout.Item(block, i)}; });
  anchor->AddElements(IndexRange(n), [&](int i) {
    return std::make_pair(std::array<int, 1>{layout.Item(block, i)},
                          Eigen::Vector2d(problem.x().segment<2>(layout.Index(block, i, 0))));
  });
  smooth->AddElements(IndexRange(n - 2), [&](int i) {
    return std::array<int, 3>{layout.Item(block, i), layout.Item(block, i + 1),
                              layout.Item(block, i + 2)};
  });
  return problem;
}

TEST(TermTest, TermsGiveTheIteratesOfHandWrittenFamilies) {
  Problem hand = MakeCircleProblem(12, 0.05);
  Problem terms = MakeCircleTermProblem(12, 0.05);
  ASSERT_NEAR((hand.x() - terms.x()).norm(), 0.0, 1e-15);
  SolverOptions options;
  options.max_iterations = 8;
  options.residual_tolerance = 0.0;
  options.step_tolerance = 0.0;
  const SolverSummary a = Solve(options, &hand), b = Solve(options, &terms);
  ASSERT_EQ(a.num_steps(), 8);
  ASSERT_EQ(b.num_steps(), 8);
  // Derived pattern: a circle row touches 2 scalars, an anchor row 1, a smooth row 3 (the
  // hand-written Smooth declares no RowTouches, so its rows count all 6 scalars).
  EXPECT_EQ(b.jacobian_nonzeros, 12 * 2 + 12 * 2 + 10 * 2 * 3);
  EXPECT_EQ(a.jacobian_nonzeros, 12 * 2 + 12 * 2 + 10 * 2 * 6);
  for (int k = 0; k <= 8; ++k)
    EXPECT_NEAR(a.iterations[k].energy, b.iterations[k].energy,
                1e-12 * std::max(1.0, a.iterations[k].energy))
        << "iteration " << k;
  EXPECT_LT((hand.x() - terms.x()).lpNorm<Eigen::Infinity>(), 1e-12);
}

TEST(TermTest, CeresSolvesATermProblemFromTheSameDefinition) {
  Problem hand = MakeCircleProblem(12, 0.05);
  Problem terms = MakeCircleTermProblem(12, 0.05);
  CeresOptions options;
  const CeresSummary a = SolveWithCeres(options, &hand);
  const CeresSummary b = SolveWithCeres(options, &terms);
  ASSERT_TRUE(b.IsSolutionUsable()) << b.BriefReport();
  EXPECT_NEAR(a.final_cost, b.final_cost, 1e-10 * a.final_cost);
  EXPECT_LT((hand.x() - terms.x()).lpNorm<Eigen::Infinity>(), 1e-6);
  EXPECT_LT(b.final_cost, 0.5 * b.initial_cost);
}

TEST(TermTest, QuadraticPerElementDataAndAWrongDeclaration) {
  // Targets as data: one model per element, each exact.
  Problem problem;
  problem.layout().AddBlock("p", 1, 2);  // item 0
  problem.layout().AddBlock("s", 1, 1);  // item 1
  auto* targets = problem.AddTerm<double, 1, 2>(
      "targets", [](double t, const auto* p, auto* r) { r[0] = p[0] * p[1] - t; });
  targets->DeclareQuadratic();
  targets->Add({0}, 1.5);
  targets->Add({0}, -2.0);
  targets->Prepare();
  const double p[2] = {0.7, -3.0};
  double phi = 0.0, jac[2];
  targets->EvaluateElement(1, p, &phi, jac);
  EXPECT_DOUBLE_EQ(phi, 0.7 * -3.0 + 2.0);
  EXPECT_DOUBLE_EQ(jac[0], -3.0);
  EXPECT_DOUBLE_EQ(jac[1], 0.7);
  // A cubic row declared quadratic is refused, naming the term, element and row.
  auto* cubic =
      problem.AddTerm<1, 1>("cubic", [](const auto* p, auto* r) { r[0] = p[0] * p[0] * p[0]; });
  cubic->DeclareQuadratic();
  cubic->Add({1});
  try {
    cubic->Prepare();
    FAIL() << "a cubic row passed as quadratic";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("term 'cubic', element 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("row 0"), std::string::npos) << e.what();
  }
}

// Items that are not in the layout or of the wrong size, and a second family of a name, are
// refused when added, naming the family, element, item and block (not a crash in Solve).
TEST(TermTest, AddRefusesItemsOutsideTheLayoutWrongSizesAndDuplicateNames) {
  Problem problem;
  const int points = problem.layout().AddBlock("points", 3, 2);
  problem.layout().AddBlock("normals", 2, 3);
  problem.ResizeToLayout();
  auto* pair = problem.AddTerm<1, 2, 2>(
      "pair", [](const auto* a, const auto* b, auto* r) { r[0] = a[0] * b[1] - a[1] * b[0]; });
  pair->Add({problem.layout().Item(points, 0), problem.layout().Item(points, 2)});
  const auto message = [&](const std::array<int, 2>& items) {
    try {
      pair->Add(items);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message({0, 7}),
            "family 'pair', element 1: item 1 (id 7) is not in the layout (it has 5 items)");
  EXPECT_EQ(message({-1, 0}),
            "family 'pair', element 1: item 0 (id -1) is not in the layout (it has 5 items)");
  EXPECT_EQ(message({0, 3}),
            "family 'pair', element 1: item 1 (id 3) of block 'normals' has 3 scalars; the family "
            "takes 2");
  EXPECT_EQ(pair->num_elements(), 1);
  EXPECT_THROW((problem.AddTerm<1, 2>("pair", [](const auto* a, auto* r) { r[0] = a[0]; })),
               std::invalid_argument);
  // A moved problem keeps checking against its own layout.
  Problem moved = std::move(problem);
  auto* again = static_cast<decltype(pair)>(moved.FindFamily("pair"));
  EXPECT_THROW(again->Add({0, 9}), std::invalid_argument);
  again->Add({1, 2});
  EXPECT_EQ(again->num_elements(), 2);
}

TEST(TermTest, UpdateRefreshesFrozenDataFromTheIterate) {
  // r = p − c with c frozen at x^k's rounded value: the update sees each iterate.
  Problem problem;
  const int block = problem.layout().AddBlock("p", 1, 1);
  problem.ResizeToLayout();
  problem.x()[0] = 2.7;
  auto* term = problem.AddTerm<double, 1, 1>(
      "frozen", [](double c, const auto* p, auto* r) { r[0] = p[0] - c; });
  term->Add({problem.layout().Item(block, 0)}, 0.0);
  std::vector<double> seen;
  term->SetUpdate([&](double& c, const double* p) {
    seen.push_back(p[0]);
    c = std::floor(p[0]);
  });
  term->Update(problem.layout(), problem.x());
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0], 2.7);
  EXPECT_EQ(term->data(0), 2.0);
  double phi = 0.0, jac = 0.0;
  term->EvaluateElement(0, problem.x().data(), &phi, &jac);
  EXPECT_NEAR(phi, 0.7, 1e-15);
  EXPECT_EQ(jac, 1.0);
}

}  // namespace
}  // namespace gproj
