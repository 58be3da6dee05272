#pragma once
// Per-face values as colours a person reads at a glance: a sequential map from blue (good,
// small) through yellow to red (large), on a logarithmic scale for values that span decades
// (planarity), written into PLY face properties (red, green, blue: MeshLab and Blender show
// them) and SVG pictures.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

using Rgb = std::array<std::uint8_t, 3>;

// Values from `min` (blue) to `max` (red), on a log10 scale when `logarithmic`.
struct ColourScale {
  std::string measure;  // what the colours show, e.g. "planarity"
  double min = 0.0, max = 1.0;
  bool logarithmic = false;
};

// A scale over `values`: logarithmic from max(min value, max value · 1e-6) when `logarithmic`
// (non-positive values take the bottom colour), linear otherwise.
ColourScale ScaleFor(const std::string& measure, const std::vector<double>& values,
                     bool logarithmic);

Rgb ColourOf(double value, const ColourScale& scale);
std::vector<Rgb> ColoursOf(const std::vector<double>& values, const ColourScale& scale);

// The mesh as an ASCII PLY with exact vertex coordinates and one colour per face.
// colours.size() must equal the number of faces.
std::string ColouredPlyText(const PolyMesh& mesh, const std::vector<Rgb>& colours);

}  // namespace gproj
