#pragma once
// Reading small line-oriented text inputs (guide files, curves, closed strips): lines split
// into words with their 1-based numbers, '#' comments dropped, and numbers and indices parsed
// with one-line InputError messages that name "<path>:<line>" and the offending word.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "gproj/common/input_error.h"

namespace gproj {

// A non-blank line of a text file: its 1-based number and its words.
struct TextLine {
  int number = 0;
  std::vector<std::string> words;
};

// The whole text file. Throws InputError naming it when it cannot be read or would not fit in
// memory.
std::string ReadTextFile(const std::string& path);
// The non-blank lines of `path` after dropping '#' comments, split at whitespace (and at
// commas when `commas_separate`). Throws InputError when the file cannot be read or has no
// such line.
std::vector<TextLine> ReadTextLines(const std::string& path, bool commas_separate = false);
// The same for text held in memory (a leading byte-order mark dropped); `name` stands for the
// path in messages.
std::vector<TextLine> SplitTextLines(const std::string& text, const std::string& name,
                                     bool commas_separate = false);

// Throws InputError "<path>: cannot read the file: it is a directory" (or "... not a regular
// file", for a FIFO, device or socket, which can block forever or never end) when `path` exists
// and is not a regular file. A missing file passes: opening it reports that.
void CheckRegularFile(const std::string& path);

// "<path>:<line>" for messages.
std::string TextPlace(const std::string& path, int line);

// The whole word as a finite number; throws InputError "<where>: '<word>' is not a number"
// (or "is not finite").
double ParseNumber(const std::string& word, const std::string& where);
// The whole word as an index in [0, count); `what` names the kind ("vertex") for the message.
int ParseIndex(const std::string& word, const std::string& where, int count,
               const std::string& what);

// Points, one per line: three numbers separated by spaces or commas. Needs at least
// `min_points`; a point repeating the previous one is refused.
std::vector<Eigen::Vector3d> ReadPoints(const std::string& path, int min_points = 2);

}  // namespace gproj
