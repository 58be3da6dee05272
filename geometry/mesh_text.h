#pragma once
// Internal to mesh I/O: the pieces the format readers share (messages, tokenising, number
// parsing) and the readers themselves, one source file per format. Conventions for every
// message: one line, "<path>:<line>: " when the source line is known and "<path>: " otherwise;
// vertex and face numbers are 0-based indices in file order.

#include <OpenMesh/Core/System/omstream.hh>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/mesh_io.h"

namespace gproj {
namespace mesh_io_internal {

enum class Format { kObj, kOff, kPly };

// "<path>:<line>: " or "<path>: ".
std::string Where(const std::string& path, int line);
[[noreturn]] void Fail(const std::string& path, int line, const std::string& what);
// A token as it appears in a message: quoted, shortened, printable.
std::string Quote(std::string_view token);
std::string QuotePath(const std::string& path);
std::string ErrnoText();
std::string LowerExtension(const std::string& path);

// Silences OpenMesh's own logging (omerr/omlog) for its lifetime: the library prints nothing,
// and every failure is reported through InputError instead.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : err_enabled_(::omerr().is_enabled()), log_enabled_(::omlog().is_enabled()) {
    ::omerr().disable();
    ::omlog().disable();
  }
  ~QuietOpenMesh() {
    // Flushing while disabled discards what was buffered.
    ::omerr().flush();
    ::omlog().flush();
    if (err_enabled_) ::omerr().enable();
    if (log_enabled_) ::omlog().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool err_enabled_;
  bool log_enabled_;
};

// The file opened in binary mode; fails naming it when it is a directory or cannot be opened.
std::ifstream OpenForReading(const std::string& path);
std::string ReadWholeFile(const std::string& path);
bool IsBlank(std::string_view text);

// Yields the lines of a text without their '#' comments, with 1-based line numbers (a '\r'
// before the '\n' is left to the tokenizer as whitespace).
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  bool Next(std::string_view* line, int* line_number) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view raw = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_number_;
    const std::size_t hash = raw.find('#');
    if (hash != std::string_view::npos) raw = raw.substr(0, hash);
    *line = raw;
    *line_number = line_number_;
    return true;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_number_ = 0;
};

std::vector<std::string_view> Tokens(std::string_view line);
// Next line with at least one token; false at the end of the text.
bool NextTokens(LineReader* reader, std::vector<std::string_view>* tokens, int* line_number);
// Locale-independent; accepts a leading '+', "nan" and "inf" (rejected later as non-finite).
bool ParseDouble(std::string_view token, double* value);
bool ParseInt(std::string_view token, long long* value);
// Appends the vertex given by tokens[first..first+3) (x y z) of `line`.
void AddVertex(const std::string& path, int line, const std::vector<std::string_view>& tokens,
               std::size_t first, PolygonSoup* soup);
// A non-negative element count that fits an int.
int ParseCount(const std::string& path, int line, std::string_view token, const char* what);

// The readers (obj_reader.cc, off_reader.cc, ply_reader.cc).
PolygonSoup ReadObj(const std::string& path, std::string_view text);
PolygonSoup ReadOff(const std::string& path, std::string_view text);
PolygonSoup ReadPly(const std::string& path);

}  // namespace mesh_io_internal
}  // namespace gproj
