#pragma once
// Reading the H-net JSON that `gproj hnet` writes (docs/formats.md): vertices, quad faces and
// four positive corner weights per face (HNetJson writes it).

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj::nets {

// An H-net: the quad mesh and the corner weights of each face's rational bilinear patch, in
// the order of the face's vertices as the mesh iterates them.
struct HNetPatchwork {
  PolyMesh mesh;
  std::vector<std::array<double, 4>> weights;
  // The document's other keys (e.g. input_vertices of a diagonal net), kept for what is written
  // from it.
  nlohmann::json extra = nlohmann::json::object();
};

// The largest ratio of two corner weights of one patch: beyond it the patch degenerates
// towards its heavier corners (and products of weights leave double range).
inline constexpr double kMaxCornerWeightRatio = 1e12;

// Parses {"vertices": [[x, y, z], ...], "faces": [[i0, i1, i2, i3], ...], "weights": [[w0, w1,
// w2, w3], ...]} (other keys are ignored). Throws InputError naming `name` and the key and index
// of the problem: not JSON (or a number beyond double range), a missing key, a point that is not
// three finite numbers, a face that is not four integer vertex ids in range, a vertex no face
// uses, a weight that is not a positive finite number, corner weights of one patch that differ
// by more than kMaxCornerWeightRatio, a weight row per face missing, and what BuildMesh refuses
// (quads only, manifold, no degenerate face).
HNetPatchwork ParseHNetJson(const std::string& text, const std::string& name);

// At most this many faces are read (the patches of an H-net are sampled and measured).
inline constexpr long long kMaxHNetJsonFaces = 2'000'000;

}  // namespace gproj::nets
