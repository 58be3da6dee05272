#include "gproj/problems/nets/hnet_json.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace gproj::nets {
namespace {

using Json = nlohmann::json;

const Json& Key(const Json& root, const char* key, const std::string& pre) {
  const auto it = root.find(key);
  if (it == root.end()) throw InputError(pre + "missing key \"" + key + "\"");
  if (!it->is_array()) throw InputError(pre + "\"" + key + "\" must be an array");
  return *it;
}

std::string Place(const char* key, std::size_t i) {
  return std::string(key) + "[" + std::to_string(i) + "]";
}

// row as `count` finite numbers.
std::vector<double> Numbers(const Json& row, std::size_t count, const std::string& what,
                            const std::string& pre) {
  if (!row.is_array() || row.size() != count)
    throw InputError(pre + what + ": expected " + std::to_string(count) + " numbers");
  std::vector<double> out;
  for (std::size_t k = 0; k < count; ++k) {
    if (!row[k].is_number())
      throw InputError(pre + what + "[" + std::to_string(k) + "] is not a number");
    const double x = row[k].get<double>();
    if (!std::isfinite(x))
      throw InputError(pre + what + "[" + std::to_string(k) + "] is not finite");
    out.push_back(x);
  }
  return out;
}

}  // namespace

HNetPatchwork ParseHNetJson(const std::string& text, const std::string& name) {
  const std::string pre = name.empty() ? "" : name + ": ";
  RefuseNulByte(text, pre);
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw InputError(pre + "not valid JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const Json::exception&) {
    throw InputError(pre + "a number is beyond the range of a double (e.g. 1e999)");
  }
  if (!root.is_object())
    throw InputError(pre + "expected an H-net: a JSON object with vertices, faces and weights");
  const Json& vertices = Key(root, "vertices", pre);
  const Json& faces = Key(root, "faces", pre);
  const Json& weights = Key(root, "weights", pre);
  if (faces.empty()) throw InputError(pre + "\"faces\" is empty");
  if (static_cast<long long>(faces.size()) > kMaxHNetJsonFaces)
    throw InputError(pre + "\"faces\" has " + std::to_string(faces.size()) +
                     " entries; gproj reads H-nets of at most " +
                     std::to_string(kMaxHNetJsonFaces) + " patches");
  if (weights.size() != faces.size())
    throw InputError(pre + "\"weights\" has " + std::to_string(weights.size()) + " rows for " +
                     std::to_string(faces.size()) +
                     " faces (one row of four corner weights per face)");
  PolygonSoup soup;
  soup.vertices.reserve(vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const std::vector<double> p = Numbers(vertices[v], 3, Place("vertices", v), pre);
    soup.vertices.emplace_back(p[0], p[1], p[2]);
    soup.vertex_lines.push_back(0);
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Json& row = faces[f];
    if (!row.is_array() || row.size() != 4)
      throw InputError(pre + Place("faces", f) +
                       ": expected four vertex ids (H-net patches are "
                       "quads)");
    std::vector<int> face;
    for (std::size_t k = 0; k < 4; ++k) {
      if (!row[k].is_number_integer() || row[k].get<long long>() < 0 ||
          row[k].get<long long>() >= static_cast<long long>(vertices.size()))
        throw InputError(pre + Place("faces", f) + "[" + std::to_string(k) +
                         "]: expected an integer vertex id in [0, " +
                         std::to_string(vertices.size()) + ")");
      face.push_back(row[k].get<int>());
    }
    soup.faces.push_back(face);
    soup.face_lines.push_back(0);
  }
  std::vector<char> used(vertices.size(), 0);
  for (const std::vector<int>& face : soup.faces)
    for (int v : face) used[v] = 1;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (!used[v])
      throw InputError(pre + Place("vertices", v) +
                       " is used by no face (an H-net's vertices are its patches' corners)");
  HNetPatchwork hnet;
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it.key() != "vertices" && it.key() != "faces" && it.key() != "weights")
      hnet.extra[it.key()] = it.value();
  hnet.weights.resize(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::vector<double> w = Numbers(weights[f], 4, Place("weights", f), pre);
    for (int k = 0; k < 4; ++k) {
      if (!(w[k] > 0.0)) {
        char text[64];
        std::snprintf(text, sizeof(text), "] = %g", w[k]);
        throw InputError(pre + Place("weights", f) + "[" + std::to_string(k) + text +
                         " is not positive (an H-net's corner weights are positive)");
      }
      hnet.weights[f][k] = w[k];
    }
    const double ratio =
        *std::max_element(w.begin(), w.end()) / *std::min_element(w.begin(), w.end());
    if (!(ratio <= kMaxCornerWeightRatio)) {
      char text[160];
      std::snprintf(text, sizeof(text),
                    ": the corner weights differ by a factor %.3g, more than %g (the patch "
                    "degenerates towards its heavier corners)",
                    ratio, kMaxCornerWeightRatio);
      throw InputError(pre + Place("weights", f) + text);
    }
  }
  MeshRequirements requirements;
  requirements.quads_only = true;
  hnet.mesh = BuildMesh(soup, name, requirements);
  // The weights follow the face's vertices as given; the mesh may iterate them from another
  // corner.
  for (auto f : hnet.mesh.faces()) {
    const int first = hnet.mesh.fv_begin(f)->idx();
    const std::vector<int>& given = soup.faces[f.idx()];
    int shift = 0;
    while (shift < 4 && given[shift] != first) ++shift;
    std::array<double, 4> rotated{};
    for (int k = 0; k < 4; ++k) rotated[k] = hnet.weights[f.idx()][(k + shift) % 4];
    hnet.weights[f.idx()] = rotated;
  }
  return hnet;
}

}  // namespace gproj::nets
