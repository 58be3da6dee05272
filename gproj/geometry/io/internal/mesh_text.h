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

#include "gproj/geometry/io/mesh_io.h"

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
// The whole file; fails up front when holding it would need more memory than the machine has.
std::string ReadWholeFile(const std::string& path);
bool IsBlank(std::string_view text);
// `text` without a leading UTF-8 byte-order mark (EF BB BF).
std::string_view WithoutByteOrderMark(std::string_view text);

// Size checks before allocating. Tokens need a byte each and a separator between them, so
// `tokens` tokens cannot fit in fewer than 2 × tokens − 1 bytes; "<where><what>, which need at
// least N bytes, but the file has only B bytes <after>" otherwise.
void CheckTokensFit(const std::string& path, int line, const std::string& what, double tokens,
                    std::size_t available, const std::string& after);
// gproj::CheckMemory with the place: "<path>:<line>: <what> needs about N GB of memory, …".
void CheckMemory(const std::string& path, int line, const std::string& what, double bytes);
// Bytes to read and build a mesh: the polygon soup, the OpenMesh mesh and the edge map of the
// validation, per vertex, face and face corner (rounded up; an estimate for CheckMemory).
double MeshMemoryEstimate(double vertices, double faces, double corners);
// `bytes` for messages: "123 bytes", "4.2 GB".
std::string ByteCount(double bytes);

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

// The whitespace-separated tokens of a text with their 1-based line numbers, read one at a time,
// so that a record may span lines. '\r' is whitespace (CRLF files read as LF ones); with
// `hash_comments`, '#' starts a comment that runs to the end of its line.
struct Token {
  std::string_view text;
  int line = 0;
};
class TokenReader {
 public:
  TokenReader(std::string_view text, bool hash_comments)
      : text_(text), hash_comments_(hash_comments) {}
  // The next token; false at the end of the text.
  bool Next(Token* token);
  // The next token only when it is on `line`; false (consuming nothing) otherwise.
  bool NextOnLine(int line, Token* token);
  // Drops the tokens left on `line` (colours and normals after a record).
  void SkipRestOfLine(int line);
  // Bytes not yet read.
  std::size_t remaining() const { return text_.size() - pos_; }
  // The line the reader is on (1-based).
  int line() const { return line_; }

 private:
  void SkipSpaceAndComments();

  std::string_view text_;
  bool hash_comments_;
  std::size_t pos_ = 0;
  int line_ = 1;
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
PolygonSoup ReadPly(const std::string& path, std::string_view data);

}  // namespace mesh_io_internal
}  // namespace gproj
