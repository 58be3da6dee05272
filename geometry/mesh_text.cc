#include "geometry/mesh_text.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <system_error>

namespace gproj {
namespace mesh_io_internal {

namespace fs = std::filesystem;

std::string Where(const std::string& path, int line) {
  return line > 0 ? path + ":" + std::to_string(line) + ": " : path + ": ";
}

[[noreturn]] void Fail(const std::string& path, int line, const std::string& what) {
  throw InputError(Where(path, line) + what);
}

// A token as it appears in a message: quoted, shortened, printable.
std::string Quote(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown;
  for (char c : token.substr(0, kMaxShown)) {
    shown += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  }
  if (token.size() > kMaxShown) shown += "...";
  return "\"" + shown + "\"";
}

std::string QuotePath(const std::string& path) { return "\"" + path + "\""; }

std::string ErrnoText() { return std::strerror(errno); }

std::string LowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::ifstream OpenForReading(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) Fail(path, 0, "cannot read the file: it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    Fail(path, 0,
         "cannot open the file for reading: " +
             (errno != 0 ? ErrnoText() : std::string("unknown error")));
  }
  return in;
}

std::string ReadWholeFile(const std::string& path) {
  std::ifstream in = OpenForReading(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) Fail(path, 0, "cannot read the file: " + ErrnoText());
  return text;
}

bool IsBlank(std::string_view text) {
  return std::all_of(text.begin(), text.end(),
                     [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
}

std::vector<std::string_view> Tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

// Next line with at least one token; false at the end of the text.
bool NextTokens(LineReader* reader, std::vector<std::string_view>* tokens, int* line_number) {
  std::string_view line;
  while (reader->Next(&line, line_number)) {
    *tokens = Tokens(line);
    if (!tokens->empty()) return true;
  }
  return false;
}

// Locale-independent; accepts a leading '+', "nan" and "inf" (rejected later as non-finite).
bool ParseDouble(std::string_view token, double* value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  const char* begin = token.data();
  const char* end = begin + token.size();
  const auto [ptr, ec] = std::from_chars(begin, end, *value);
  if (ec == std::errc::result_out_of_range && ptr == end) {
    // Overflow gives ±inf, underflow gives 0 or a subnormal, as strtod does.
    *value = std::strtod(std::string(token).c_str(), nullptr);
    return true;
  }
  return ec == std::errc() && ptr == end;
}

bool ParseInt(std::string_view token, long long* value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

void AddVertex(const std::string& path, int line, const std::vector<std::string_view>& tokens,
               std::size_t first, PolygonSoup* soup) {
  const std::size_t vertex = soup->vertices.size();
  const std::size_t given = tokens.size() - first;
  if (given < 3) {
    Fail(path, line,
         "vertex " + std::to_string(vertex) + " has " + std::to_string(given) +
             (given == 1 ? " coordinate" : " coordinates") + "; 3 are required");
  }
  Eigen::Vector3d p;
  for (int k = 0; k < 3; ++k) {
    const std::string_view token = tokens[first + k];
    if (!ParseDouble(token, &p[k])) {
      Fail(path, line,
           "vertex " + std::to_string(vertex) + " has a malformed coordinate " + Quote(token));
    }
    if (!std::isfinite(p[k])) {
      Fail(path, line,
           "vertex " + std::to_string(vertex) + " has a non-finite coordinate " + Quote(token));
    }
  }
  soup->vertices.push_back(p);
  soup->vertex_lines.push_back(line);
}

int ParseCount(const std::string& path, int line, std::string_view token, const char* what) {
  long long count = 0;
  if (!ParseInt(token, &count) || count < 0 || count > std::numeric_limits<int>::max()) {
    Fail(path, line, std::string("malformed ") + what + " count " + Quote(token));
  }
  return static_cast<int>(count);
}

}  // namespace mesh_io_internal
}  // namespace gproj
