#include "gproj/problems/marionette/marionette_inputs.h"

#include "gproj/geometry/io/text_input.h"

namespace gproj::marionette {

namespace {

// A guide file's lines; `path` names it in messages.
MarionetteGuideFile GuidesFromLines(const std::vector<TextLine>& lines, const std::string& path,
                                    int num_vertices) {
  MarionetteGuideFile file;
  for (const TextLine& line : lines) {
    const std::string where = TextPlace(path, line.number);
    const std::vector<std::string>& w = line.words;
    if (w[0] == "guide" && w.size() >= 5) {
      MarionetteGuide g;
      g.where = where;
      g.start = ParseIndex(w[1], where, num_vertices, "vertex");
      g.next = ParseIndex(w[2], where, num_vertices, "vertex");
      for (size_t k = 3; k < w.size(); ++k) g.values.push_back(ParseNumber(w[k], where));
      file.guides.push_back(std::move(g));
    } else if (w[0] == "vertex" && w.size() == 3) {
      file.vertices.push_back(
          {ParseIndex(w[1], where, num_vertices, "vertex"), ParseNumber(w[2], where)});
    } else {
      throw InputError(where +
                       ": expected 'guide START NEXT VALUE VALUE ...' (two values at least) or "
                       "'vertex ID VALUE'");
    }
  }
  return file;
}

}  // namespace

MarionetteGuideFile ReadMarionetteGuides(const std::string& path, int num_vertices) {
  return GuidesFromLines(ReadTextLines(path), path, num_vertices);
}

MarionetteGuideFile ParseMarionetteGuides(const std::string& text, const std::string& name,
                                          int num_vertices) {
  return GuidesFromLines(SplitTextLines(text, name), name, num_vertices);
}

namespace {

ClosedStripFile ClosedStripFromLines(const std::vector<TextLine>& lines, const std::string& path) {
  ClosedStripFile file;
  std::vector<double> heights;
  std::vector<int> line_of;
  size_t words = 0;
  for (const TextLine& line : lines) {
    const std::string where = TextPlace(path, line.number);
    if (words == 0) words = line.words.size();
    if (line.words.size() < 5 || line.words.size() % 2 == 0 || line.words.size() != words)
      throw InputError(where + ": expected " +
                       (words >= 5 && words % 2 == 1 ? std::to_string(words) + " numbers"
                                                     : std::string("5, 7, 9, ... numbers")) +
                       " (inner x y z, then x y of every outer curve), got " +
                       std::to_string(line.words.size()));
    std::vector<double> v;
    for (const std::string& w : line.words) v.push_back(ParseNumber(w, where));
    if (file.curves.empty()) file.curves.resize((words - 3) / 2 + 1);
    file.curves[0].emplace_back(v[0], v[1]);
    heights.push_back(v[2]);
    for (size_t c = 1; c < file.curves.size(); ++c)
      file.curves[c].emplace_back(v[1 + 2 * c], v[2 + 2 * c]);
    line_of.push_back(line.number);
  }
  const int n = static_cast<int>(heights.size());
  if (n < 3)
    throw InputError(path + ": a closed strip needs at least 3 vertex pairs, got " +
                     std::to_string(n));
  for (size_t ring = 0; ring + 1 < file.curves.size(); ++ring) {
    const ClosedStrip strip{file.curves[ring], file.curves[ring + 1]};
    const int i = DegenerateClosedStripQuad(strip);
    if (i < 0) continue;
    const int k = (i + 1) % n;
    throw InputError(TextPlace(path, line_of[i]) + ": quad " + std::to_string(i) +
                     (file.curves.size() > 2 ? " of ring " + std::to_string(ring) : "") +
                     " (vertex pairs " + std::to_string(i) + " and " + std::to_string(k) +
                     ", lines " + std::to_string(line_of[i]) + " and " +
                     std::to_string(line_of[k]) + ") has a degenerate plan view: inner " +
                     std::to_string(i) + ", outer " + std::to_string(i) + " and inner " +
                     std::to_string(k) + " are collinear in x, y");
  }
  file.strip = {file.curves[0], file.curves[1]};
  file.inner_heights = Eigen::Map<const Eigen::VectorXd>(heights.data(), n);
  return file;
}

}  // namespace

ClosedStripFile ReadClosedStrip(const std::string& path) {
  return ClosedStripFromLines(ReadTextLines(path), path);
}

ClosedStripFile ParseClosedStrip(const std::string& text, const std::string& name) {
  return ClosedStripFromLines(SplitTextLines(text, name), name);
}

std::vector<MarionetteTarget> GridGuideValues(const GridShape& shape,
                                              const std::vector<double>& row,
                                              const std::vector<double>& column) {
  if (static_cast<int>(row.size()) != shape.cols + 1 ||
      static_cast<int>(column.size()) != shape.rows + 1)
    throw InputError("guide curves need " + std::to_string(shape.cols + 1) + " row values and " +
                     std::to_string(shape.rows + 1) + " column values, got " +
                     std::to_string(row.size()) + " and " + std::to_string(column.size()));
  std::vector<MarionetteTarget> values;
  for (int j = 0; j <= shape.cols; ++j) values.push_back({shape.Vertex(0, j), row[j]});
  for (int i = 0; i <= shape.rows; ++i) values.push_back({shape.Vertex(i, 0), column[i]});
  return values;
}

MarionetteProjectionOptions MarionetteProjectionFromValues(const std::string& name,
                                                           const std::vector<double>& axis,
                                                           const std::vector<double>& centre) {
  MarionetteProjectionOptions projection;
  if (!ParseMarionetteProjection(name, &projection.type))
    throw InputError("`projection` must be vertical, cylindrical or central, not '" + name + "'");
  if (axis.size() != 6)
    throw InputError("`axis` needs six numbers px,py,pz,dx,dy,dz, got " +
                     std::to_string(axis.size()));
  if (centre.size() != 3)
    throw InputError("`centre` needs three numbers x,y,z, got " + std::to_string(centre.size()));
  projection.axis_point = Eigen::Vector3d(axis[0], axis[1], axis[2]);
  projection.axis_direction = Eigen::Vector3d(axis[3], axis[4], axis[5]);
  projection.centre = Eigen::Vector3d(centre[0], centre[1], centre[2]);
  return projection;
}

}  // namespace gproj::marionette
