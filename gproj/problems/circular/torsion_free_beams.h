#pragma once
// Torsion-free beams on a circular mesh (000 §4.3: "a grid structure with a torsion-free beam
// layout. The offset was computed with a reflection rule similar to the one generating cyclidic
// nets. An optimisation was performed in order to minimise the height gap at the nodes between
// beams of constant height").
//
// Node axes: the axis n_i at one node is chosen; across every edge e = (i, j) the next is its
// mirror image in the edge's bisector plane, n_j = n_i − 2 (n_i · ê) ê. The two axes of an edge
// and the edge then lie in one plane (the beam's plane: the node is torsion-free), and
// v_j + h n_j − (v_i + h n_i) is parallel to the edge, so the offset mesh v + h n at any
// constant distance h is parallel to the mesh. Around a face the mirror images close exactly
// when the face is inscribed in a circle (the mirror planes all contain the circle's axis):
// circular meshes have such vertex offsets (Pottmann, Liu, Wallner, Bobenko, Wang 2007,
// "Geometry of multi-layer freeform structures for architecture", §3).
//
// Beams of constant height h: the top edge of the beam on e lies in its plane at distance h
// from e, so it meets both node axes at λ_e = h / |n_i × ê| (a mirror image keeps the angle).
// Beams meeting at a node reach its axis at different λ_e: the height gap at the node is
// max λ_e − min λ_e. The axes depend only on the first one, n_v = M_v n_0 (M_v a product of
// reflections); the first axis is chosen to minimise the squared gaps (Ceres, on the sphere).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj::circular {

struct BeamOptions {
  double height = 0.0;  // h > 0: beam height, and the offset distance along the axes
  double width = 0.0;   // beam thickness across its plane; 0: 4% of the mean edge length
  // Choose the first axis to minimise the height gaps; false: the first node's mean face normal.
  bool optimise = true;
  // Largest closing angle (radians) of the axes around a face: a larger one means the face is
  // not inscribed in a circle and the input is refused.
  double circularity_tolerance = 1e-6;
  bool IsValid(std::string* why) const;
};

struct BeamLayout {
  std::vector<Eigen::Vector3d> axis;  // unit node axis per vertex, pointing to the offset side
  std::vector<double> edge_lift;      // λ_e per edge (OpenMesh edge index)
  std::vector<double> node_gap;       // max λ − min λ over the node's beams, per vertex
  PolyMesh offset;                    // v + h n: parallel to the input
  PolyMesh beams;                     // one closed box (6 quads) per edge
  // Measures (the report's keys): max_beam_planarity (corner distance from the beam's plane /
  // mean edge), max_offset_angle (radians between an edge and its offset),
  // max_offset_distance_error
  // (| |h n| − h | / h), max_closing_angle (radians, around the faces), max_height_gap and
  // mean_height_gap (/ h), initial_max_height_gap (/ h, before the optimisation).
  NamedValues measures;
  int root = 0;  // the node whose axis was chosen
};

// Throws InputError for invalid options, a mesh that is not connected, a face not inscribed in
// a circle (naming the face and its closing angle) or an axis along an edge.
BeamLayout TorsionFreeBeams(const PolyMesh& mesh, const BeamOptions& options);

// The node axes as OBJ line segments from each vertex to vertex + length · axis.
std::string AxesObj(const PolyMesh& mesh, const std::vector<Eigen::Vector3d>& axis, double length);

}  // namespace gproj::circular
