#include "geometry/text_input.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace gproj {

namespace {

// The whole file, without a leading UTF-8 byte-order mark.
std::string ReadTextFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": cannot read the file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": read error");
  return text;
}

}  // namespace

std::vector<TextLine> ReadTextLines(const std::string& path, bool commas_separate) {
  return SplitTextLines(ReadTextFile(path), path, commas_separate);
}

std::vector<TextLine> SplitTextLines(const std::string& text, const std::string& name,
                                     bool commas_separate) {
  const std::size_t start = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  std::vector<TextLine> lines;
  int number = 0;
  for (std::size_t pos = start; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    // '\r' (of CRLF line ends) is whitespace for the split below.
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    line = line.substr(0, line.find('#'));
    if (commas_separate)
      for (char& c : line)
        if (c == ',') c = ' ';
    std::istringstream words(line);
    TextLine text_line{number, {}};
    for (std::string word; words >> word;) text_line.words.push_back(word);
    if (!text_line.words.empty()) lines.push_back(std::move(text_line));
  }
  if (lines.empty()) throw InputError(name + ": the file is empty");
  return lines;
}

std::string TextPlace(const std::string& path, int line) {
  return path + ":" + std::to_string(line);
}

double ParseNumber(const std::string& word, const std::string& where) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(word, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != word.size()) throw InputError(where + ": '" + word + "' is not a number");
  if (!std::isfinite(value)) throw InputError(where + ": '" + word + "' is not finite");
  return value;
}

int ParseIndex(const std::string& word, const std::string& where, int count,
               const std::string& what) {
  const double v = ParseNumber(word, where);
  if (v != std::floor(v) || v < 0 || v >= count)
    throw InputError(where + ": '" + word + "' is not a " + what + " id (0-based, there are " +
                     std::to_string(count) + ")");
  return static_cast<int>(v);
}

std::vector<Eigen::Vector3d> ReadPoints(const std::string& path, int min_points) {
  std::vector<Eigen::Vector3d> points;
  for (const TextLine& line : ReadTextLines(path, /*commas_separate=*/true)) {
    const std::string where = TextPlace(path, line.number);
    if (line.words.size() != 3)
      throw InputError(where + ": a point needs 3 coordinates, got " +
                       std::to_string(line.words.size()));
    Eigen::Vector3d p;
    for (int i = 0; i < 3; ++i) p[i] = ParseNumber(line.words[i], where);
    if (!points.empty() && (p - points.back()).norm() == 0.0)
      throw InputError(where + ": repeats the previous point");
    points.push_back(p);
  }
  if (static_cast<int>(points.size()) < min_points)
    throw InputError(path + ": needs at least " + std::to_string(min_points) + " points, got " +
                     std::to_string(points.size()));
  return points;
}

}  // namespace gproj
