#include "gproj/problems/weingarten/curvature_diagram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace gproj::weingarten {
namespace {

// K from a signed square root s = sign(K)·√|K|.
double KFromRoot(double s) { return s * std::abs(s); }

// Deterministic pseudo-random values in [0, 1) (no dependence on the standard library's
// distributions).
class Lcg {
 public:
  explicit Lcg(std::uint64_t seed) : state_(seed) {}
  double Next() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

 private:
  std::uint64_t state_;
};

void RandomSamples(int n, std::uint64_t seed, std::vector<double>* h, std::vector<double>* k) {
  Lcg rng(seed);
  h->resize(n);
  k->resize(n);
  for (int i = 0; i < n; ++i) {
    (*h)[i] = 2.0 * rng.Next() - 0.5;
    (*k)[i] = KFromRoot(3.0 * rng.Next() - 1.0);
  }
}

// Three blobs of 3 × 3 samples along the diagonal of the (H, √K) box, at normalised positions
// [0, 0.05], [0.275, 0.325] and [0.95, 1]. Grids of 4, 5 and 6 cells per axis keep each blob in
// one cell; 7 cells cut the middle blob (at 2/7) in both directions.
TEST(ClusterMoldsTest, ThreeSeparatedBlobsGiveThreeMolds) {
  const double centres[3] = {0.025, 0.3, 0.975};
  std::vector<double> h, k;
  std::vector<int> blob;
  for (int b = 0; b < 3; ++b)
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j) {
        const double u = centres[b] + 0.025 * i, v = centres[b] + 0.025 * j;
        h.push_back(3.0 + 4.0 * u);             // H ∈ [3, 7]
        k.push_back(KFromRoot(4.0 * v - 2.0));  // √K ∈ [−2, 2]: the outer blobs differ in sign
        blob.push_back(b);
      }
  const MoldClustering c = ClusterMolds(h, k, 3);
  EXPECT_EQ(c.num_clusters, 3);
  EXPECT_EQ(c.cells_per_axis, 6);
  ASSERT_EQ(c.cluster.size(), h.size());
  for (size_t i = 0; i < h.size(); ++i) EXPECT_EQ(c.cluster[i], blob[i]) << "sample " << i;
  EXPECT_EQ(c.cluster_size, (std::vector<int>{9, 9, 9}));
}

// √K keeps K's sign: elliptic and hyperbolic samples of equal |K| need different molds.
TEST(ClusterMoldsTest, SignOfKSeparatesMolds) {
  const MoldClustering c = ClusterMolds({1.0, 1.0, 1.0, 1.0}, {4.0, -4.0, 4.0, -4.0}, 2);
  EXPECT_EQ(c.num_clusters, 2);
  EXPECT_EQ(c.cluster, (std::vector<int>{0, 1, 0, 1}));
  EXPECT_EQ(c.cluster_size, (std::vector<int>{2, 2}));
}

TEST(ClusterMoldsTest, OneMoldHoldsEverything) {
  std::vector<double> h, k;
  RandomSamples(200, 1, &h, &k);
  const MoldClustering c = ClusterMolds(h, k, 1);
  EXPECT_EQ(c.num_clusters, 1);
  EXPECT_EQ(c.cells_per_axis, 1);
  EXPECT_EQ(c.cluster, std::vector<int>(200, 0));
  EXPECT_EQ(c.cluster_size, std::vector<int>{200});
}

TEST(ClusterMoldsTest, IdsInRangeFirstSeenAndSizesSumToTheSampleCount) {
  std::vector<double> h, k;
  RandomSamples(500, 2, &h, &k);
  for (int max_clusters : {2, 5, 17, 40, 100}) {
    SCOPED_TRACE(max_clusters);
    const MoldClustering c = ClusterMolds(h, k, max_clusters);
    EXPECT_GE(c.num_clusters, 1);
    EXPECT_LE(c.num_clusters, max_clusters);
    ASSERT_EQ(static_cast<int>(c.cluster_size.size()), c.num_clusters);
    std::vector<int> counted(c.num_clusters, 0);
    int next_new = 0;
    for (int id : c.cluster) {
      ASSERT_GE(id, 0);
      ASSERT_LT(id, c.num_clusters);
      ASSERT_LE(id, next_new);  // ids appear in first-seen order
      if (id == next_new) ++next_new;
      ++counted[id];
    }
    EXPECT_EQ(counted, c.cluster_size);
    EXPECT_EQ(std::accumulate(c.cluster_size.begin(), c.cluster_size.end(), 0), 500);
  }
}

TEST(ClusterMoldsTest, MoreMoldsNeverGiveACoarserGrid) {
  for (std::uint64_t seed : {3, 4, 5}) {
    std::vector<double> h, k;
    RandomSamples(300, seed, &h, &k);
    int previous_cells = 0, previous_clusters = 0;
    for (int max_clusters = 1; max_clusters <= 120; ++max_clusters) {
      const MoldClustering c = ClusterMolds(h, k, max_clusters);
      EXPECT_GE(c.cells_per_axis, previous_cells) << "seed " << seed << ", " << max_clusters;
      EXPECT_LE(c.num_clusters, max_clusters);
      if (c.cells_per_axis == previous_cells) {
        EXPECT_EQ(c.num_clusters, previous_clusters);  // same grid, same cells
      }
      previous_cells = c.cells_per_axis;
      previous_clusters = c.num_clusters;
    }
    EXPECT_GT(previous_clusters, 60) << "seed " << seed;
  }
}

// Grids of n and n + 1 cells are not nested, so the finest admissible grid can occupy fewer cells
// than a coarser grid admitted under a smaller bound: here 5 × 5 cells give 4 molds, 3 × 3 give 5.
// The finer grid wins on both counts (smaller cells, fewer molds).
TEST(ClusterMoldsTest, FinestGridCanNeedFewerMoldsThanACoarserOne) {
  const std::vector<double> h = {0, 1, 8, 6, 5, 4, 6};
  const std::vector<double> k = {100, 64, 0, 16, 16, 1, 25};  // √K = 10, 8, 0, 4, 4, 1, 5
  const MoldClustering five = ClusterMolds(h, k, 5);
  EXPECT_EQ(five.cells_per_axis, 3);
  EXPECT_EQ(five.num_clusters, 5);
  const MoldClustering six = ClusterMolds(h, k, 6);
  EXPECT_EQ(six.cells_per_axis, 5);
  EXPECT_EQ(six.num_clusters, 4);
}

TEST(ClusterMoldsTest, ZeroWidthAxisClustersAlongTheOther) {
  std::vector<double> h, k(10, 0.0);
  for (int i = 0; i < 10; ++i) h.push_back(i);
  const MoldClustering ten = ClusterMolds(h, k, 10);
  EXPECT_EQ(ten.cells_per_axis, 10);  // every sample alone: refining further changes nothing
  EXPECT_EQ(ten.num_clusters, 10);
  const MoldClustering nine = ClusterMolds(h, k, 9);
  EXPECT_EQ(nine.cells_per_axis, 9);
  EXPECT_EQ(nine.num_clusters, 9);
  EXPECT_EQ(nine.cluster[8], nine.cluster[9]);
  EXPECT_EQ(nine.cluster_size.back(), 2);
}

TEST(ClusterMoldsTest, CoincidentSamplesStopTheSearchAtOneCell) {
  const MoldClustering c = ClusterMolds({0.3, 0.3, 0.3}, {-2.0, -2.0, -2.0}, 5);
  EXPECT_EQ(c.cells_per_axis, 1);
  EXPECT_EQ(c.num_clusters, 1);
  EXPECT_EQ(c.cluster_size, std::vector<int>{3});
}

TEST(ClusterMoldsTest, NearCoincidentSamplesStopAtTheGridCap) {
  const MoldClustering c = ClusterMolds({0.0, 1e-13, 1.0}, {0.0, 0.0, 0.0}, 3);
  EXPECT_EQ(c.cells_per_axis, 4096);
  EXPECT_EQ(c.num_clusters, 2);
}

TEST(ClusterMoldsTest, RejectsBadInput) {
  EXPECT_THROW(ClusterMolds({}, {}, 3), std::invalid_argument);
  EXPECT_THROW(ClusterMolds({1.0, 2.0}, {1.0}, 3), std::invalid_argument);
  EXPECT_THROW(ClusterMolds({1.0}, {1.0}, 0), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ClusterMolds({1.0, nan}, {1.0, 2.0}, 3), std::invalid_argument);
  EXPECT_THROW(ClusterMolds({1.0, 2.0}, {1.0, INFINITY}, 3), std::invalid_argument);
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// Tags balance, the root is <svg>, text holds no raw '<' or '>', and every '&' starts an entity.
// Returns an empty string when the document is well-formed, else what is wrong.
std::string XmlProblem(const std::string& doc) {
  std::vector<std::string> open;
  bool seen_root = false;
  for (size_t p = 0; p < doc.size();) {
    if (doc[p] == '<') {
      const size_t end = doc.find('>', p);
      if (end == std::string::npos) return "unterminated tag at " + std::to_string(p);
      const std::string tag = doc.substr(p + 1, end - p - 1);
      if (tag.find('<') != std::string::npos) return "'<' inside tag at " + std::to_string(p);
      if (!tag.empty() && tag[0] == '/') {
        if (open.empty() || open.back() != tag.substr(1)) return "mismatched </" + tag + ">";
        open.pop_back();
      } else if (tag.empty() || tag.back() != '/') {
        const std::string name = tag.substr(0, tag.find_first_of(" \n"));
        if (open.empty() && (seen_root || name != "svg")) return "root is not a single <svg>";
        seen_root = true;
        open.push_back(name);
      } else if (open.empty()) {
        return "element outside the root at " + std::to_string(p);
      }
      p = end + 1;
      continue;
    }
    if (doc[p] == '>') return "raw '>' at " + std::to_string(p);
    if (doc[p] == '&') {
      bool entity = false;
      for (const char* e : {"&amp;", "&lt;", "&gt;", "&quot;"})
        entity = entity || doc.compare(p, std::string(e).size(), e) == 0;
      if (!entity) return "raw '&' at " + std::to_string(p);
    }
    ++p;
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  return seen_root ? "" : "no root";
}

TEST(CurvatureDiagramTest, TitleLabelsAxesAndOneCirclePerFinitePoint) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  DiagramSeries before{
      "before", "#c0392b", {0.1, 0.5, nan, 0.9, 1.2}, {0.2, -0.1, 0.3, INFINITY, 0.0}};
  DiagramSeries after{"after", "#2e86c1", {0.4, 0.45, 0.5}, {0.05, 0.06, 0.07}};
  DiagramOptions options;
  options.title = "Weingarten tower";
  const std::string svg = RenderCurvatureDiagramSvg({before, after}, options);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(XmlProblem(svg), "");
  EXPECT_EQ(Count(svg, "<circle"), 3 + 3);
  EXPECT_EQ(Count(svg, ">Weingarten tower</text>"), 1);
  EXPECT_EQ(Count(svg, ">before (n = 3)</text>"), 1);
  EXPECT_EQ(Count(svg, ">after (n = 3)</text>"), 1);
  EXPECT_EQ(Count(svg, ">H</text>"), 1);
  EXPECT_EQ(Count(svg, ">K</text>"), 1);
  EXPECT_EQ(Count(svg, "fill=\"#c0392b\""), 2);  // legend swatch and point group
}

TEST(CurvatureDiagramTest, EscapesTextAndAttributes) {
  DiagramSeries s{"H & K <raw>", "#000\"", {0.0, 1.0}, {0.0, 1.0}};
  DiagramOptions options;
  options.title = "a < b & c > d";
  const std::string svg = RenderCurvatureDiagramSvg({s}, options);
  EXPECT_EQ(XmlProblem(svg), "");
  EXPECT_NE(svg.find(">a &lt; b &amp; c &gt; d</text>"), std::string::npos);
  EXPECT_NE(svg.find(">H &amp; K &lt;raw&gt; (n = 2)</text>"), std::string::npos);
  EXPECT_NE(svg.find("fill=\"#000&quot;\""), std::string::npos);
}

TEST(CurvatureDiagramTest, NiceTicksWithLabels) {
  DiagramSeries s{"s", "blue", {0.0, 0.5, 1.0}, {-300.0, 100.0, 500.0}};
  const std::string svg = RenderCurvatureDiagramSvg({s});
  // H ∈ [0, 1] in steps of 0.2; K ∈ [−300, 500] in steps of 100. Both axes label 0.
  EXPECT_EQ(Count(svg, ">0</text>"), 2);
  for (const char* label : {">0.2</text>", ">0.4</text>", ">1.0</text>", ">-300</text>",
                            ">-100</text>", ">100</text>", ">500</text>"})
    EXPECT_EQ(Count(svg, label), 1) << label;
  EXPECT_EQ(Count(svg, ">0.3</text>"), 0);
  EXPECT_EQ(Count(svg, ">50</text>"), 0);
  EXPECT_EQ(Count(svg, ">600</text>"), 0);  // ticks stay inside the padded range
}

// The dashed group holds the H = 0 and K = 0 lines.
int ZeroLines(const std::string& svg) {
  const size_t begin = svg.find("stroke-dasharray");
  return Count(svg.substr(begin, svg.find("</g>", begin) - begin), "<line");
}

TEST(CurvatureDiagramTest, ZeroLinesOnlyInsideTheRange) {
  EXPECT_EQ(ZeroLines(RenderCurvatureDiagramSvg({{"s", "red", {-1.0, 2.0}, {-3.0, 1.0}}})), 2);
  EXPECT_EQ(ZeroLines(RenderCurvatureDiagramSvg({{"s", "red", {-1.0, 2.0}, {1.0, 3.0}}})), 1);
  EXPECT_EQ(ZeroLines(RenderCurvatureDiagramSvg({{"s", "red", {1.0, 2.0}, {1.0, 3.0}}})), 0);
}

TEST(CurvatureDiagramTest, LargeSeriesAreSubsampled) {
  DiagramSeries s{"many", "green", {}, {}};
  for (int i = 0; i < 50000; ++i) {
    s.h.push_back(std::cos(i * 0.001));
    s.k.push_back(std::sin(i * 0.001));
  }
  const std::string svg = RenderCurvatureDiagramSvg({s});
  EXPECT_EQ(Count(svg, "<circle"), 20000);
  EXPECT_NE(svg.find(">many (n = 50000)</text>"), std::string::npos);
}

TEST(CurvatureDiagramTest, DegenerateDataStillGivesAFrame) {
  const std::string single = RenderCurvatureDiagramSvg({{"one", "red", {2.0}, {2.0}}});
  EXPECT_EQ(XmlProblem(single), "");
  EXPECT_EQ(Count(single, "<circle"), 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string none = RenderCurvatureDiagramSvg({{"none", "red", {nan}, {0.0}}});
  EXPECT_EQ(XmlProblem(none), "");
  EXPECT_EQ(Count(none, "<circle"), 0);
  EXPECT_NE(none.find(">none (n = 0)</text>"), std::string::npos);
}

TEST(CurvatureDiagramTest, RejectsMismatchedSeriesAndTinyCanvases) {
  EXPECT_THROW(RenderCurvatureDiagramSvg({{"s", "red", {1.0, 2.0}, {1.0}}}), std::invalid_argument);
  DiagramOptions tiny;
  tiny.width = 50;
  EXPECT_THROW(RenderCurvatureDiagramSvg({}, tiny), std::invalid_argument);
}

}  // namespace
}  // namespace gproj::weingarten
