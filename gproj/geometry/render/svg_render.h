#pragma once
// A picture of a mesh a person can open in any browser: an SVG of its faces seen from a given
// direction (orthographic), flat Lambert shading, back-to-front painter's order.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

struct SvgOptions {
  Eigen::Vector3d view = Eigen::Vector3d(0.7, -1.0, 1.6);   // direction from the scene to the eye
  Eigen::Vector3d light = Eigen::Vector3d(0.4, -0.5, 1.0);  // direction towards the light
  int width = 900;                                          // pixels; height follows the aspect
  std::string title;
  // One colour per face (FaceColours), shaded; empty: the default blue-grey.
  std::vector<std::array<std::uint8_t, 3>> face_colours;
  // A line under the title, e.g. the colour scale.
  std::string legend;
  // Line segments drawn over the faces (a direction field, say), and dots (singularities).
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  std::string segment_colour = "rgb(200,40,40)";
  std::vector<Eigen::Vector3d> dots;
  std::string dot_colour = "rgb(220,0,0)";
};

// The SVG document. Throws InputError if the mesh has no faces or non-finite points.
std::string RenderMeshSvg(const PolyMesh& mesh, const SvgOptions& options = {});

}  // namespace gproj
