#pragma once
// Curvature diagrams and mold clustering (003 §4.2, Fig. 5, Fig. 13d).
// A curvature diagram plots (H, K) per sample; a Weingarten surface's diagram is a curve.
// Mold clustering works in the (H, √K) plane (same scale on both axes; √K is taken with K's
// sign, sign(K)·√|K|): a uniform grid over the points' bounding box is refined (1, 2, 3, ...
// cells per axis) as long as the points occupy at most the asked number of cells; the occupied
// cells of the finest such grid are the clusters (one mold each).

#include <string>
#include <vector>

namespace gproj {

struct MoldClustering {
  int cells_per_axis = 0;    // of the grid used
  int num_clusters = 0;      // occupied cells (≤ the asked number)
  std::vector<int> cluster;  // per point: 0 .. num_clusters − 1, numbered in first-seen order
  std::vector<int> cluster_size;
};

// h, k: one value per sample (same length, finite). max_clusters ≥ 1. Throws std::invalid_argument
// on empty or mismatched input.
MoldClustering ClusterMolds(const std::vector<double>& h, const std::vector<double>& k,
                            int max_clusters);

struct DiagramSeries {
  std::string label;  // e.g. "before", "after"
  std::string colour;  // SVG colour, e.g. "#c0392b"
  std::vector<double> h, k;
};

struct DiagramOptions {
  int width = 640, height = 480;  // pixels
  std::string title;
};

// An SVG scatter plot of the series in the (H, K) plane with axes, ticks, labels and a legend.
// Non-finite points are skipped.
std::string RenderCurvatureDiagramSvg(const std::vector<DiagramSeries>& series,
                                      const DiagramOptions& options = {});

}  // namespace gproj
