#include "gproj/geometry/io/internal/mesh_text.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <system_error>

#include "gproj/geometry/io/text_input.h"

#ifndef _WIN32
#endif

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
  CheckRegularFile(path);
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
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (!ec) CheckMemory(path, 0, "reading the file", static_cast<double>(size));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) Fail(path, 0, "cannot read the file: " + ErrnoText());
  return text;
}

bool IsBlank(std::string_view text) {
  return std::all_of(text.begin(), text.end(),
                     [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
}

std::string_view WithoutByteOrderMark(std::string_view text) {
  constexpr std::string_view kMark = "\xEF\xBB\xBF";
  if (text.substr(0, kMark.size()) == kMark) text.remove_prefix(kMark.size());
  return text;
}

std::string ByteCount(double bytes) {
  if (bytes < 1e9) return std::to_string(static_cast<long long>(bytes)) + " bytes";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.3g GB", bytes / 1e9);
  return buffer;
}

void CheckTokensFit(const std::string& path, int line, const std::string& what, double tokens,
                    std::size_t available, const std::string& after) {
  const double needed = 2.0 * tokens - 1.0;
  if (needed > static_cast<double>(available)) {
    Fail(path, line,
         what + ", which need at least " + ByteCount(needed) + ", but the file has only " +
             ByteCount(static_cast<double>(available)) + " " + after);
  }
}

void CheckMemory(const std::string& path, int line, const std::string& what, double bytes) {
  gproj::CheckMemory(Where(path, line) + what, bytes);
}

double MeshMemoryEstimate(double vertices, double faces, double corners) {
  // Soup: a point and a line number per vertex, a vector and a line per face, an int per
  // corner. Mesh: a point, a handle and status per vertex, two halfedges per corner, a handle
  // per face. Validation: about one edge map entry per corner.
  constexpr double kPerVertex = 28 + 48, kPerFace = 28 + 16 + 8, kPerCorner = 4 + 48 + 64;
  return kPerVertex * vertices + kPerFace * faces + kPerCorner * corners;
}

void TokenReader::SkipSpaceAndComments() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++pos_;
    } else if (c == '#' && hash_comments_) {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      return;
    }
  }
}

bool TokenReader::Next(Token* token) {
  SkipSpaceAndComments();
  if (pos_ >= text_.size()) return false;
  const std::size_t begin = pos_;
  while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])) &&
         !(hash_comments_ && text_[pos_] == '#')) {
    ++pos_;
  }
  token->text = text_.substr(begin, pos_ - begin);
  token->line = line_;
  return true;
}

bool TokenReader::NextOnLine(int line, Token* token) {
  const std::size_t pos = pos_;
  const int current = line_;
  if (Next(token) && token->line == line) return true;
  pos_ = pos;
  line_ = current;
  return false;
}

void TokenReader::SkipRestOfLine(int line) {
  Token ignored;
  while (NextOnLine(line, &ignored)) {
  }
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
