#include "gproj/geometry/io/text_input.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace gproj {

std::string ReadTextFile(const std::string& path) {
  CheckRegularFile(path);
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) CheckMemory(path + ": the file", 2.0 * static_cast<double>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": read error");
  return text;
}

void CheckRegularFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status) || fs::is_regular_file(status)) return;
  throw InputError(path + ": cannot read the file: " +
                   (fs::is_directory(status)
                        ? std::string("it is a directory")
                        : std::string("it is not a regular file (a FIFO, device or socket)")));
}

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
  // strtod, not stod: an underflow to a subnormal or zero is a number (stod throws for it), an
  // overflow gives ±inf and is refused below.
  char* end = nullptr;
  const double value = word.empty() ? 0.0 : std::strtod(word.c_str(), &end);
  // Decimal notation only: strtod also reads hexadecimal ("0x10" is 16), which no geometry file
  // means.
  if (word.empty() || end != word.c_str() + word.size() ||
      std::isspace(static_cast<unsigned char>(word[0])) ||
      word.find_first_of("xX") != std::string::npos)
    throw InputError(where + ": '" + word + "' is not a number");
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
    if (!points.empty() && p == points.back())
      throw InputError(where + ": repeats the previous point");
    points.push_back(p);
  }
  if (static_cast<int>(points.size()) < min_points)
    throw InputError(path + ": needs at least " + std::to_string(min_points) + " points, got " +
                     std::to_string(points.size()));
  return points;
}

}  // namespace gproj
