#pragma once
// Curvature diagrams and mold clustering (003 §4.2, Fig. 5, Fig. 13d).
// A curvature diagram plots (H, K) per sample; a Weingarten surface's diagram is a curve.
// Mold clustering works in the (H, √K) plane (same scale on both axes; √K is taken with K's
// sign, sign(K)·√|K|): a uniform grid over the points' bounding box is refined (1, 2, 3, ...
// cells per axis) as long as the points occupy at most the asked number of cells; the occupied
// cells of the finest such grid are the clusters (one mold each).

#include <string>
#include <vector>

namespace gproj::weingarten {

struct MoldClustering {
  int cells_per_axis = 0;    // of the grid used
  int num_clusters = 0;      // occupied cells (≤ the asked number)
  std::vector<int> cluster;  // per point: 0 .. num_clusters − 1, numbered in first-seen order
  std::vector<int> cluster_size;
};

// h, k: one value per sample (same length, finite). max_clusters ≥ 1. The search stops at the first
// grid with more than max_clusters occupied cells, once every distinct (H, √K) pair has a cell of
// its own, or at 4096 cells per axis; the grid before the stop is returned. More allowed clusters
// never give a coarser grid, but grids of n and n + 1 cells are not nested, so the finer grid may
// occupy fewer cells. Cost: O(#samples) per grid tried. Throws std::invalid_argument on empty,
// mismatched or non-finite input, or max_clusters < 1.
MoldClustering ClusterMolds(const std::vector<double>& h, const std::vector<double>& k,
                            int max_clusters);

struct DiagramSeries {
  std::string label;   // e.g. "before", "after"
  std::string colour;  // SVG colour, e.g. "#c0392b"
  std::vector<double> h, k;
};

struct DiagramOptions {
  int width = 640, height = 480;  // pixels
  std::string title;
};

// An SVG scatter plot of the series in the (H, K) plane: 1-2-5 ticks with labels, axis titles, the
// H = 0 and K = 0 lines when in range, a legend with each label and its count of finite points,
// the title on top. Non-finite points are skipped; a series with more than 20000 finite points is
// drawn as a uniform subsample of 20000. Text and colours are XML-escaped. Throws
// std::invalid_argument if a series' h and k differ in length or the canvas is below 200 × 150.
std::string RenderCurvatureDiagramSvg(const std::vector<DiagramSeries>& series,
                                      const DiagramOptions& options = {});

}  // namespace gproj::weingarten
