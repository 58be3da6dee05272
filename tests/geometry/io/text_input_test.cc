#include "gproj/geometry/io/text_input.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/surface/bspline_surface.h"

namespace gproj {
namespace {

namespace fs = std::filesystem;

std::string WriteTemp(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / ("gproj_text_input_" + name);
  std::ofstream(path) << text;
  return path.string();
}

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(TextInputTest, LinesKeepTheirNumbersAndDropComments) {
  const std::string path = WriteTemp("lines.txt", "# head\n\na b  # tail\n  c,d\n");
  const std::vector<TextLine> lines = ReadTextLines(path);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].number, 3);
  EXPECT_EQ(lines[0].words, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(lines[1].words, (std::vector<std::string>{"c,d"}));
  EXPECT_EQ(ReadTextLines(path, true)[1].words, (std::vector<std::string>{"c", "d"}));
}

TEST(TextInputTest, ByteOrderMarkAndCrlfAreAccepted) {
  const std::string path = WriteTemp("bom.txt",
                                     "\xEF\xBB\xBF"
                                     "0 0 0\r\n# comment\r\n1,2,3\r\n\r\n4 5 6");
  const std::vector<Eigen::Vector3d> points = ReadPoints(path);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0], Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(points[2], Eigen::Vector3d(4, 5, 6));
  const std::vector<TextLine> lines =
      ReadTextLines(WriteTemp("bom_guide.txt", "\xEF\xBB\xBFguide 0 1 2 3\r\nvertex 4 5\r\n"));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].words, (std::vector<std::string>{"guide", "0", "1", "2", "3"}));
  EXPECT_EQ(lines[1].number, 2);
  EXPECT_EQ(lines[1].words.back(), "5");
}

TEST(TextInputTest, DirectoryIsRefusedByName) {
  const std::string dir = fs::temp_directory_path().string();
  EXPECT_EQ(MessageOf([&] { ReadTextLines(dir); }),
            dir + ": cannot read the file: it is a directory");
}

// A FIFO would block the reader forever: it is refused like a directory, and so by every reader.
TEST(TextInputTest, FifoIsRefusedByName) {
  const std::string fifo = (fs::temp_directory_path() / "gproj_text_input_fifo.obj").string();
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string expected = fifo +
                               ": cannot read the file: it is not a regular file (a FIFO, "
                               "device or socket)";
  EXPECT_EQ(MessageOf([&] { ReadTextLines(fifo); }), expected);
  EXPECT_EQ(MessageOf([&] { ReadMesh(fifo); }), expected);
  EXPECT_EQ(MessageOf([&] { ReadBSplineJson(fifo); }), expected);
  fs::remove(fifo);
}

// Underflow is a number (a subnormal or zero), not an error; overflow is not finite.
TEST(TextInputTest, TinyNumbersAreNumbers) {
  EXPECT_EQ(ParseNumber("1.6532732e-316", "f:1"), 1.6532732e-316);
  EXPECT_EQ(ParseNumber("1e-400", "f:1"), 0.0);
  EXPECT_EQ(MessageOf([] { ParseNumber("1e400", "f:2"); }), "f:2: '1e400' is not finite");
  EXPECT_EQ(MessageOf([] { ParseNumber(" 1", "f:3"); }), "f:3: ' 1' is not a number");
}

TEST(TextInputTest, NumbersAndIndicesAreCheckedWhole) {
  EXPECT_EQ(ParseNumber("-2.5e1", "f:1"), -25.0);
  EXPECT_EQ(MessageOf([] { ParseNumber("1.5x", "f:1"); }), "f:1: '1.5x' is not a number");
  EXPECT_EQ(MessageOf([] { ParseNumber("0x10", "f:1"); }), "f:1: '0x10' is not a number");
  EXPECT_EQ(MessageOf([] { ParseNumber("inf", "f:2"); }), "f:2: 'inf' is not finite");
  EXPECT_EQ(ParseIndex("3", "f:1", 4, "vertex"), 3);
  EXPECT_NE(MessageOf([] { ParseIndex("4", "f:1", 4, "vertex"); }).find("'4' is not a vertex id"),
            std::string::npos);
  EXPECT_NE(MessageOf([] { ParseIndex("1.5", "f:1", 4, "vertex"); }).find("not a vertex id"),
            std::string::npos);
}

TEST(TextInputTest, PointsNeedThreeFiniteDistinctCoordinates) {
  EXPECT_EQ(ReadPoints(WriteTemp("p.txt", "0 0 0\n1,2,3\n")).size(), 2u);
  EXPECT_NE(MessageOf([] {
              ReadPoints(WriteTemp("q.txt", "0 0 0\n1 2\n"));
            }).find("q.txt:2: a point needs 3 coordinates, got 2"),
            std::string::npos);
  EXPECT_NE(MessageOf([] {
              ReadPoints(WriteTemp("r.txt", "0 0 0\n0 0 0\n"));
            }).find("r.txt:2: repeats the previous point"),
            std::string::npos);
  // Distinct points 1e-300 apart are distinct (their distance used to underflow to 0).
  EXPECT_EQ(ReadPoints(WriteTemp("t.txt", "1e-300 0 0\n2e-300 0 0\n")).size(), 2u);
  EXPECT_NE(MessageOf([] {
              ReadPoints(WriteTemp("s.txt", "0 0 0\n"));
            }).find("needs at least 2 points, got 1"),
            std::string::npos);
  EXPECT_NE(MessageOf([] { ReadTextLines(WriteTemp("e.txt", "# only\n")); }).find("is empty"),
            std::string::npos);
}

}  // namespace
}  // namespace gproj
