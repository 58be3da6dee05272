#include "gproj/geometry/io/mesh_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace gproj {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// A (nu × nv)-quad grid on a curved, non-round surface; faces consistently oriented.
PolygonSoup GridSoup(int nu, int nv) {
  PolygonSoup soup;
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      soup.vertices.emplace_back(i / 3.0 + 0.1, j * std::sqrt(2.0) / 7.0,
                                 std::sin(0.7 * i) * std::cos(0.3 * j) / 9.0 + 1e-7 / 3.0);
    }
  }
  const auto id = [nu](int i, int j) { return j * (nu + 1) + i; };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      soup.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return soup;
}

std::string ObjText(const PolygonSoup& soup) {
  std::ostringstream out;
  out.precision(17);
  out << "# quad grid\n";
  for (const Eigen::Vector3d& p : soup.vertices) {
    out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  for (const std::vector<int>& face : soup.faces) {
    out << 'f';
    for (int v : face) out << ' ' << v + 1;
    out << '\n';
  }
  return out.str();
}

std::string OffText(const PolygonSoup& soup) {
  std::ostringstream out;
  out.precision(17);
  out << "OFF\n# quad grid\n" << soup.vertices.size() << ' ' << soup.faces.size() << " 0\n";
  for (const Eigen::Vector3d& p : soup.vertices) {
    out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  for (const std::vector<int>& face : soup.faces) {
    out << face.size();
    for (int v : face) out << ' ' << v;
    out << '\n';
  }
  return out.str();
}

// The InputError message thrown by `f`; a failure if nothing is thrown.
template <class F>
std::string InputErrorMessage(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  ADD_FAILURE() << "no InputError was thrown";
  return "";
}

void ExpectSameMesh(const PolygonSoup& expected, const PolyMesh& mesh) {
  ASSERT_EQ(mesh.n_vertices(), expected.vertices.size());
  ASSERT_EQ(mesh.n_faces(), expected.faces.size());
  for (const auto vh : mesh.vertices()) {
    const Eigen::Vector3d& want = expected.vertices[vh.idx()];
    const PolyMesh::Point& got = mesh.point(vh);
    const Eigen::Vector3d got_eigen(got[0], got[1], got[2]);
    EXPECT_LE((got_eigen - want).norm(), 1e-15 * want.norm()) << "vertex " << vh.idx();
  }
  for (const auto fh : mesh.faces()) {
    std::vector<int> face;
    for (const auto vh : mesh.fv_range(fh)) face.push_back(vh.idx());
    // OpenMesh may start a face's cycle at another vertex; compare as cycles.
    std::vector<int> want = expected.faces[fh.idx()];
    ASSERT_EQ(face.size(), want.size());
    const auto start = std::find(want.begin(), want.end(), face[0]);
    ASSERT_NE(start, want.end()) << "face " << fh.idx();
    std::rotate(want.begin(), start, want.end());
    EXPECT_EQ(face, want) << "face " << fh.idx();
  }
}

class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::path(::testing::TempDir()) /
           ("gproj_mesh_io_" + name + "_" + std::to_string(std::random_device{}()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = Path(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  std::vector<std::string> DirectoryEntries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  static std::string ReadText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// Round trips.

TEST_F(MeshIoTest, ObjQuadGridRoundTrip) {
  const PolygonSoup grid = GridSoup(5, 4);
  const std::string in = Write("grid.obj", ObjText(grid));

  const PolygonSoup soup = ReadPolygonSoup(in);
  ASSERT_EQ(soup.vertices.size(), 30u);
  ASSERT_EQ(soup.faces.size(), 20u);
  EXPECT_EQ(soup.vertex_lines.front(), 2);  // after the comment line
  EXPECT_EQ(soup.face_lines.front(), 32);   // 1 comment + 30 vertices + 1
  EXPECT_EQ(soup.faces[0], grid.faces[0]);
  const PolyMesh mesh = BuildMesh(soup, in, {/*quads_only=*/true});
  ExpectSameMesh(grid, mesh);

  const std::string out = Path("out.obj");
  WriteMeshAtomically(mesh, out);
  ExpectSameMesh(grid, ReadMesh(out, {/*quads_only=*/true}));
  EXPECT_EQ(DirectoryEntries(), (std::vector<std::string>{"grid.obj", "out.obj"}));
}

TEST_F(MeshIoTest, OffQuadGridRoundTrip) {
  const PolygonSoup grid = GridSoup(3, 6);
  const std::string in = Write("grid.off", OffText(grid));

  const PolygonSoup soup = ReadPolygonSoup(in);
  ASSERT_EQ(soup.vertices.size(), 28u);
  ASSERT_EQ(soup.faces.size(), 18u);
  EXPECT_EQ(soup.vertex_lines.front(), 4);  // "OFF", comment, counts
  EXPECT_EQ(soup.face_lines.back(), 3 + 28 + 18);
  const PolyMesh mesh = BuildMesh(soup, in, {/*quads_only=*/true});
  ExpectSameMesh(grid, mesh);

  const std::string out = Path("out.off");
  WriteMeshAtomically(mesh, out);
  ExpectSameMesh(grid, ReadMesh(out, {/*quads_only=*/true}));
  EXPECT_EQ(DirectoryEntries(), (std::vector<std::string>{"grid.off", "out.off"}));
}

TEST_F(MeshIoTest, PlyRoundTripThroughWriteMeshAtomically) {
  const PolygonSoup grid = GridSoup(4, 4);
  const PolyMesh mesh = BuildMesh(grid, "grid", {});
  const std::string out = Path("out.ply");
  WriteMeshAtomically(mesh, out);

  // The file itself is exact: doubles in shortest round-trip form.
  const std::string text = ReadText(out);
  EXPECT_THAT(text, HasSubstr("property double x\n"));
  std::istringstream body(text.substr(text.find("end_header\n") + 11));
  for (const Eigen::Vector3d& want : grid.vertices) {
    Eigen::Vector3d got;
    body >> got.x() >> got.y() >> got.z();
    EXPECT_EQ(got, want);
  }

  const PolygonSoup soup = ReadPolygonSoup(out);
  EXPECT_EQ(soup.vertex_lines.front(), 11);  // ASCII PLY: after the 10 header lines
  EXPECT_EQ(soup.face_lines.back(), 10 + 25 + 16);
  EXPECT_EQ(soup.faces, grid.faces);
  EXPECT_EQ(soup.vertices, grid.vertices);  // doubles read back exactly
  EXPECT_EQ(ReadMesh(out, {/*quads_only=*/true}).n_faces(), 16u);
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"out.ply"});
}

TEST_F(MeshIoTest, WriteMeshReplacesAnExistingFile) {
  const std::string out = Write("out.obj", "old contents\n");
  const PolygonSoup grid = GridSoup(2, 2);
  WriteMeshAtomically(BuildMesh(grid, "grid", {}), out);
  ExpectSameMesh(grid, ReadMesh(out));
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"out.obj"});
}

TEST_F(MeshIoTest, ObjAcceptsIndexFormsAndIgnoresOtherKeywords) {
  const std::string path = Write("forms.obj",
                                 "mtllib grid.mtl\r\n"
                                 "o patch\n"
                                 "v 0 0 0\n"
                                 "v 1 0 0  # trailing comment\n"
                                 "v 1 1 0 1.0\n"
                                 "v 0 1 0\n"
                                 "vt 0 0\n"
                                 "vn 0 0 1\n"
                                 "s off\n"
                                 "usemtl steel\n"
                                 "f 1/1/1 2//1 3/1 4\n"
                                 "v 2 0 +0\n"
                                 "v 2 1 0\n"
                                 "f -5 -2 -1 -4\n"
                                 "l 1 2\n");
  const PolygonSoup soup = ReadPolygonSoup(path);
  ASSERT_EQ(soup.vertices.size(), 6u);
  EXPECT_EQ(soup.faces, (std::vector<std::vector<int>>{{0, 1, 2, 3}, {1, 4, 5, 2}}));
  EXPECT_EQ(soup.face_lines, (std::vector<int>{11, 14}));
  EXPECT_EQ(soup.vertex_lines, (std::vector<int>{3, 4, 5, 6, 12, 13}));
  EXPECT_EQ(BuildMesh(soup, path, {/*quads_only=*/true}).n_faces(), 2u);
}

TEST_F(MeshIoTest, OffAcceptsCountsOnTheHeaderLineAndFaceColours) {
  const std::string path = Write("colour.off",
                                 "COFF 4 1 0\n"
                                 "0 0 0 255 0 0 255\n"
                                 "1 0 0 255 0 0 255\n"
                                 "\n"
                                 "1 1 0 255 0 0 255\n"
                                 "0 1 0 255 0 0 255\n"
                                 "4 0 1 2 3 0.5 0.5 0.5\n");
  const PolygonSoup soup = ReadPolygonSoup(path);
  EXPECT_EQ(soup.vertex_lines, (std::vector<int>{2, 3, 5, 6}));
  EXPECT_EQ(soup.faces, (std::vector<std::vector<int>>{{0, 1, 2, 3}}));
  EXPECT_EQ(soup.face_lines, std::vector<int>{7});
}

TEST_F(MeshIoTest, IsolatedVerticesAreAllowed) {
  PolygonSoup soup = GridSoup(1, 1);
  soup.vertices.emplace_back(5.0, 5.0, 5.0);
  const PolyMesh mesh = BuildMesh(soup, "soup", {/*quads_only=*/true});
  EXPECT_EQ(mesh.n_vertices(), 5u);
  EXPECT_EQ(mesh.n_faces(), 1u);
}

TEST_F(MeshIoTest, WriteTextFileAtomicallyWritesAndReplaces) {
  const std::string path = Path("report.json");
  WriteTextFileAtomically(path, "{\"a\": 1}\n");
  EXPECT_EQ(ReadText(path), "{\"a\": 1}\n");
  WriteTextFileAtomically(path, "");
  EXPECT_EQ(ReadText(path), "");
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"report.json"});
}

// A run killed while writing leaves its hidden temporary; the next write of the same file
// removes it when its process no longer runs, and keeps those of running processes.
TEST_F(MeshIoTest, StaleTemporariesOfKilledRunsAreRemoved) {
  const std::string stale = ".out.obj.tmp-999999999.obj";  // above any pid_t of a live process
  const std::string live = ".out.obj.tmp-1.obj";           // pid 1 always runs
  const std::string other = ".other.obj.tmp-999999999.obj";
  for (const std::string& name : {stale, live, other}) std::ofstream(Path(name)) << "partial\n";
  WriteTextFileAtomically(Path("out.obj"), "# mesh\n");
  std::vector<std::string> entries = DirectoryEntries();
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{other, live, "out.obj"}));
}

// A stale backup of a replaced file (".out.obj.old-<pid>.obj") goes the same way.
TEST_F(MeshIoTest, StaleBackupsOfKilledRunsAreRemoved) {
  std::ofstream(Path(".out.obj.old-999999999.obj")) << "old\n";
  WriteTextFileAtomically(Path("out.obj"), "# mesh\n");
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"out.obj"});
}

// A run's outputs are written all or none: when the third cannot be created, the first two
// (one new, one replacing an old file) are not written either, and no temporary stays.
TEST_F(MeshIoTest, OutputFilesWriteNoneWhenOneCannotBeCreated) {
  std::ofstream(Path("old.json")) << "old report\n";
  {
    OutputFiles files;
    files.AddText(Path("mesh.obj"), "# mesh\n");
    files.AddText(Path("old.json"), "new report\n");
    const std::string missing = Path("no-such-folder/picture.svg");
    EXPECT_THAT(InputErrorMessage([&] { files.AddText(missing, "<svg/>"); }),
                StartsWith(missing + ": cannot create the temporary file"));
  }
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"old.json"});
  EXPECT_EQ(ReadText(Path("old.json")), "old report\n");
}

// When a rename fails during Commit (the target is a folder), the targets already replaced
// get their previous contents back and the new ones disappear.
TEST_F(MeshIoTest, OutputFilesCommitRollsBackWhenARenameFails) {
  std::ofstream(Path("old.json")) << "old report\n";
  fs::create_directory(Path("picture.svg"));
  std::ofstream(fs::path(Path("picture.svg")) / "inside") << "keeps the folder non-empty\n";
  OutputFiles files;
  files.AddText(Path("mesh.obj"), "# mesh\n");
  files.AddText(Path("old.json"), "new report\n");
  files.AddText(Path("picture.svg"), "<svg/>");
  const std::string message = InputErrorMessage([&] { files.Commit(); });
  EXPECT_THAT(message, StartsWith(Path("picture.svg") + ": cannot move the temporary file"));
  EXPECT_THAT(message, HasSubstr("no output written"));
  std::vector<std::string> entries = DirectoryEntries();
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"old.json", "picture.svg"}));
  EXPECT_EQ(ReadText(Path("old.json")), "old report\n");
}

TEST_F(MeshIoTest, OutputFilesCommitWritesEveryFile) {
  std::ofstream(Path("old.json")) << "old report\n";
  OutputFiles files;
  files.AddText(Path("old.json"), "new report\n");
  files.AddMesh(BuildMesh(GridSoup(1, 1), "grid", {}), Path("mesh.off"));
  files.Commit();
  std::vector<std::string> entries = DirectoryEntries();
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"mesh.off", "old.json"}));
  EXPECT_EQ(ReadText(Path("old.json")), "new report\n");
  EXPECT_EQ(ReadMesh(Path("mesh.off")).n_faces(), 1u);
}

// ---------------------------------------------------------------------------------------------
// Reading errors.

TEST_F(MeshIoTest, MissingFile) {
  const std::string path = Path("missing.obj");
  const std::string message = InputErrorMessage([&] { ReadPolygonSoup(path); });
  EXPECT_THAT(message, StartsWith(path + ": "));
  EXPECT_THAT(message, HasSubstr("cannot open the file"));
  EXPECT_THAT(message, HasSubstr("No such file"));

  const std::string ply = Path("missing.ply");
  EXPECT_THAT(InputErrorMessage([&] { ReadMesh(ply); }), StartsWith(ply + ": cannot open"));
}

TEST_F(MeshIoTest, EmptyFile) {
  for (const std::string name : {"empty.obj", "empty.off", "empty.ply"}) {
    const std::string path = Write(name, "");
    EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }), path + ": the file is empty");
  }
  const std::string blank = Write("blank.obj", "\n  \n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(blank); }), blank + ": the file is empty");
}

TEST_F(MeshIoTest, FileWithoutFaces) {
  const std::string obj = Write("points.obj", "# points only\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(obj); }), obj + ": the file has no faces");
  const std::string off = Write("points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(off); }), off + ":2: the file has no faces");
}

TEST_F(MeshIoTest, UnknownExtension) {
  const std::string path = Write("grid.stl", ObjText(GridSoup(1, 1)));
  const std::string message = InputErrorMessage([&] { ReadPolygonSoup(path); });
  EXPECT_EQ(message, path + ": unknown mesh file extension \".stl\"; expected .obj, .off or .ply");

  const PolyMesh mesh = BuildMesh(GridSoup(1, 1), "grid", {});
  const std::string out = Path("out.stl");
  EXPECT_THAT(InputErrorMessage([&] { WriteMeshAtomically(mesh, out); }),
              StartsWith(out + ": unknown mesh file extension"));
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"grid.stl"});
}

TEST_F(MeshIoTest, NanCoordinate) {
  const std::string path = Write("nan.obj",
                                 "v 0 0 0\n"
                                 "v 1 0 0\n"
                                 "# comment\n"
                                 "v 1 1 0\n"
                                 "v 0 nan 0\n"
                                 "f 1 2 3 4\n");
  const std::string message = InputErrorMessage([&] { ReadMesh(path); });
  EXPECT_EQ(message, path + ":5: vertex 3 has a non-finite coordinate \"nan\"");

  const std::string off =
      Write("inf.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 1e999\n4 0 1 2 3\n");
  EXPECT_THAT(InputErrorMessage([&] { ReadMesh(off); }),
              StartsWith(off + ":6: vertex 3 has a non-finite coordinate"));
}

TEST_F(MeshIoTest, MalformedNumbers) {
  const std::string obj = Write("bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1.2.3 0\nf 1 2 3\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(obj); }),
            obj + ":3: vertex 2 has a malformed coordinate \"1.2.3\"");
  const std::string short_vertex = Write("short.obj", "v 0 0\nf 1 1 1\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(short_vertex); }),
            short_vertex + ":1: vertex 0 has 2 coordinates; 3 are required");
  const std::string index = Write("index.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 x3\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(index); }),
            index + ":4: face 0 has a malformed vertex index \"x3\"");
  const std::string counts = Write("counts.off", "OFF\n4 one 0\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(counts); }),
            counts + ":2: malformed face count \"one\"");
}

TEST_F(MeshIoTest, ObjIndexOutOfRange) {
  std::string text = ObjText(GridSoup(5, 5));  // 36 vertices, 25 faces
  text += "f 1 2 41 3\n";                      // line 1 + 36 + 25 + 1
  const std::string path = Write("range.obj", text);
  EXPECT_EQ(
      InputErrorMessage([&] { ReadMesh(path); }),
      path + ":63: face 25 references vertex 40 (written as 41), but the file has 36 vertices");

  const std::string zero = Write("zero.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(zero); }),
            zero + ":4: face 0 uses vertex index 0; OBJ indices start at 1");
  const std::string relative = Write("relative.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -1 -2 -4\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(relative); }),
            relative + ":4: face 0 uses relative vertex index -4, but only 3 vertices precede it");
}

TEST_F(MeshIoTest, OffIndexOutOfRange) {
  const std::string path = Write("range.off",
                                 "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                 "4 0 1 2 3\n"
                                 "3 0 2 4\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }),
            path + ":8: face 1 references vertex 4, but the file has 4 vertices");
}

TEST_F(MeshIoTest, OffTruncatedOrInconsistent) {
  // The trailing comment keeps the declared counts within the file size.
  const std::string truncated =
      Write("truncated.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n# padding padding padding\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(truncated); }),
            truncated + ": the file ends after 2 of 4 vertices");
  const std::string short_face =
      Write("short_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(short_face); }),
            short_face + ":6: face 0 declares 4 vertices but lists 3");
  const std::string header = Write("header.off", "OF\n3 1 0\n");
  EXPECT_THAT(InputErrorMessage([&] { ReadMesh(header); }),
              StartsWith(header + ":1: expected the header \"OFF\""));
}

// ---------------------------------------------------------------------------------------------
// Hostile and careless input (issue 16): every defect found there, refused or read right.

const char kPlyHeader[] =
    "ply\nformat ascii 1.0\nelement vertex 4\n"
    "property double x\nproperty double y\nproperty double z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
const char kQuadBody[] = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

TEST_F(MeshIoTest, PlyPropertyBeforeAnyElementIsRefusedNamingItsLine) {
  const std::string path = Write("early.ply",
                                 "ply\nformat ascii 1.0\nproperty float x\n"
                                 "element vertex 1\nend_header\n0\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }),
            path + ":3: a \"property\" line before any \"element\" line");
}

TEST_F(MeshIoTest, PlyFormatWithoutVersionIsRefusedNotLoopedOn) {
  for (const std::string version : {"", " *.0", " 2.0"}) {
    std::string text = kPlyHeader;
    text.replace(text.find(" 1.0"), 4, version);
    const std::string path = Write("format.ply", text + kQuadBody);
    const std::string message = InputErrorMessage([&] { ReadMesh(path); });
    EXPECT_THAT(message, StartsWith(path + ":2: ")) << version;
    EXPECT_THAT(message,
                HasSubstr(version.empty() ? "expected \"format" : "unsupported PLY version"));
  }
}

TEST_F(MeshIoTest, PlyFaceCountAboveTwoToThe32IsRefusedUpFront) {
  std::string text = kPlyHeader;
  text.replace(text.find("face 1"), 6, "face 4294967297");
  const std::string path = Write("faces.ply", text + kQuadBody);
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }),
            path + ":7: element face declares 4294967297 items; at most 2147483647 are supported");
}

TEST_F(MeshIoTest, PlyCountsBeyondTheFileSizeAreRefusedBeforeAllocating) {
  const std::string binary = Write("huge.ply",
                                   "ply\nformat binary_little_endian 1.0\n"
                                   "element vertex 2000000000\n"
                                   "property float x\nproperty float y\nproperty float z\n"
                                   "element face 1\nproperty list uchar int vertex_indices\n"
                                   "end_header\n0123456789abcdef");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(binary); }),
            binary +
                ":3: element vertex declares 2000000000 vertices, which need at least 24 GB, "
                "but the file has only 16 bytes after the header");
  std::string text = kPlyHeader;
  text.replace(text.find("face 1"), 6, "face 2000000");
  const std::string ascii = Write("huge_ascii.ply", text + kQuadBody);
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(ascii); }),
            ascii +
                ":7: element face declares 2000000 faces (after the elements before it), "
                "which need at least 16000023 bytes, but the file has only 34 bytes after "
                "the header");
}

TEST_F(MeshIoTest, PlyErrorsNameTheLineOrTheElement) {
  const std::string ascii =
      Write("ascii.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n1 x 0\n0 1 0\n4 0 1 2 3\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(ascii); }),
            ascii + ":12: vertex 2 has a malformed number \"x\"");
  const std::string range =
      Write("range.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 9\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(range); }),
            range + ":14: face 0 references vertex 9, but the file has 4 vertices");
  const std::string count =
      Write("count.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n300 0 1 2 3\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(count); }),
            count + ":14: face 0 has \"300\" where a uchar is declared");
  std::string short_binary =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  short_binary += std::string(4 * 12 + 1, '\0') + std::string("\x00\x00\x00\x01", 4);
  short_binary[short_binary.size() - 5] = 1;  // a face of 1 vertex
  short_binary += std::string(8, '\0');       // within the size a face of 3 needs
  const std::string binary = Write("binary.ply", short_binary);
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(binary); }),
            binary + ": face 0 has 1 vertex; at least 3 are required");
  const std::string keyword = Write("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 4\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(keyword); }),
            keyword + ":3: unknown PLY header keyword \"elemnt\"");
  const std::string trailing = Write("trailing.ply", std::string(kPlyHeader) + kQuadBody + "7\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(trailing); }),
            trailing + ":15: unexpected \"7\" after the last element");
}

// The little-endian PLY of the unit quad with extra vertex and face properties, as `type`
// coordinates and `index` indices.
template <class Coordinate, class Index>
std::string BinaryQuadPly(bool big_endian) {
  std::string out = std::string("ply\nformat ") +
                    (big_endian ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" +
                    "comment extra properties are skipped by their type\n"
                    "element vertex 4\nproperty uchar red\n" +
                    (sizeof(Coordinate) == 4 ? "property float x\nproperty float y\n"
                                               "property float z\n"
                                             : "property double x\nproperty double y\n"
                                               "property double z\n") +
                    "property list ushort float normal\n"
                    "element face 1\nproperty list uint " +
                    (sizeof(Index) == 2 ? "short" : "uint") +
                    " vertex_index\nproperty int flags\nelement edge 2\nproperty int a\n"
                    "end_header\n";
  const auto put = [&](auto value) {
    char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    if (big_endian) std::reverse(bytes, bytes + sizeof(value));
    out.append(bytes, sizeof(value));
  };
  const double corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const auto& c : corners) {
    put(static_cast<std::uint8_t>(200));
    put(static_cast<Coordinate>(c[0] + 0.1));
    put(static_cast<Coordinate>(c[1]));
    put(static_cast<Coordinate>(0.5));
    put(static_cast<std::uint16_t>(1));
    put(1.0f);
  }
  put(static_cast<std::uint32_t>(4));
  for (Index v : {0, 1, 2, 3}) put(v);
  put(static_cast<std::int32_t>(-7));
  put(static_cast<std::int32_t>(1));
  put(static_cast<std::int32_t>(2));
  return out;
}

TEST_F(MeshIoTest, BinaryPlyInBothByteOrdersWithExtraProperties) {
  const std::string little = Write("little.ply", BinaryQuadPly<float, std::uint32_t>(false));
  const std::string big = Write("big.ply", BinaryQuadPly<double, std::int16_t>(true));
  for (const std::string& path : {little, big}) {
    const PolygonSoup soup = ReadPolygonSoup(path);
    ASSERT_EQ(soup.vertices.size(), 4u) << path;
    EXPECT_EQ(soup.faces, (std::vector<std::vector<int>>{{0, 1, 2, 3}})) << path;
    EXPECT_EQ(soup.vertices[2].y(), 1.0) << path;
    EXPECT_EQ(soup.face_lines, std::vector<int>{0}) << path;
  }
  EXPECT_EQ(ReadPolygonSoup(big).vertices[1].x(), 1.1);  // doubles exact
  EXPECT_EQ(ReadPolygonSoup(little).vertices[1].x(), static_cast<double>(1.1f));
}

TEST_F(MeshIoTest, PlyReadingPrintsNothing) {
  const std::string bad = Write("bad.ply", "ply\nformat ascii 1.0\nelement face 1\nend_header\n");
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  const std::string message = InputErrorMessage([&] { ReadMesh(bad); });
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(message, bad + ": the PLY header has no \"element vertex\" line");
}

TEST_F(MeshIoTest, OffFaceListsMaySpanLines) {
  const std::string path = Write("spanning.off",
                                 "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0.5 0\n"
                                 "4\n0 1\n2 3\n"
                                 "3 1 4 2   # a comment inside the list is fine\n");
  const PolygonSoup soup = ReadPolygonSoup(path);
  EXPECT_EQ(soup.faces, (std::vector<std::vector<int>>{{0, 1, 2, 3}, {1, 4, 2}}));
  EXPECT_EQ(soup.face_lines, (std::vector<int>{8, 11}));
  EXPECT_EQ(ReadMesh(path).n_faces(), 2u);
}

TEST_F(MeshIoTest, OffCountsBeyondTheFileSizeAreRefusedBeforeAllocating) {
  const std::string path = Write("huge.off", "OFF\n2000000000 1 0\n0 0 0\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }),
            path +
                ":2: the counts declare 2000000000 vertices and 1 faces, which need at least "
                "12 GB, but the file has only 7 bytes after the counts");
}

// Every text format with a UTF-8 byte-order mark and CRLF line ends reads as without them.
TEST_F(MeshIoTest, ByteOrderMarkAndCrlfAreAccepted) {
  const std::string bom = "\xEF\xBB\xBF";
  const auto crlf = [](std::string text) {
    for (std::size_t i = text.find('\n'); i != std::string::npos; i = text.find('\n', i + 2)) {
      text.insert(i, "\r");
    }
    return text;
  };
  const PolygonSoup grid = GridSoup(2, 1);
  const std::string obj = Write("bom.obj", bom + crlf("v 0.1 0 0\n" + ObjText(grid)));
  const PolygonSoup soup = ReadPolygonSoup(obj);
  ASSERT_EQ(soup.vertices.size(), grid.vertices.size() + 1);  // the first vertex is not dropped
  EXPECT_EQ(soup.vertices[0], Eigen::Vector3d(0.1, 0, 0));
  EXPECT_EQ(soup.faces[0], (std::vector<int>{0, 1, 4, 3}));  // indices 1-based in the file
  EXPECT_EQ(soup.face_lines[0], 9);

  const std::string off = Write("bom.off", bom + crlf(OffText(grid)));
  ExpectSameMesh(grid, ReadMesh(off));
  const std::string ply = Write("bom.ply", bom + crlf(std::string(kPlyHeader) + kQuadBody));
  const PolygonSoup quad = ReadPolygonSoup(ply);
  EXPECT_EQ(quad.faces, (std::vector<std::vector<int>>{{0, 1, 2, 3}}));
  EXPECT_EQ(quad.face_lines, std::vector<int>{14});
}

TEST_F(MeshIoTest, FaceWithManyVerticesIsCheckedInLinearithmicTime) {
  // 200000 vertices on a circle, one face: a quadratic repeated-vertex check would not finish.
  constexpr int kN = 200000;
  PolygonSoup soup;
  soup.faces.emplace_back();
  for (int v = 0; v < kN; ++v) {
    const double t = 2 * M_PI * v / kN;
    soup.vertices.emplace_back(std::cos(t), std::sin(t), 0.0);
    soup.faces[0].push_back(v);
  }
  EXPECT_EQ(BuildMesh(soup, "circle", {}).n_faces(), 1u);
  soup.faces[0].back() = 5;
  EXPECT_EQ(InputErrorMessage([&] { BuildMesh(soup, "circle", {}); }),
            "circle: face 0 uses vertex 5 more than once (degenerate face)");
}

// ---------------------------------------------------------------------------------------------
// Mesh validation.

TEST_F(MeshIoTest, NonQuadFaceWhenQuadsOnly) {
  const std::string path = Write("mixed.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                                 "f 1 2 3 4\n"
                                 "f 2 5 3\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path, {/*quads_only=*/true}); }),
            path + ":7: face 1 has 3 vertices; a quad mesh is required");
  EXPECT_EQ(ReadMesh(path).n_faces(), 2u);
}

// Degeneracy is judged at the face's own size: a unit square at 1e-150 (whose area underflows
// to 0 when computed directly) and at 1e200 (whose squared edges overflow) are valid.
TEST_F(MeshIoTest, FacesAreJudgedAtAnyFiniteScale) {
  for (const char* scale : {"1e-150", "1e200"}) {
    const std::string s = scale;
    const std::string path =
        Write(std::string("square_") + scale + ".obj",
              "v 0 0 0\nv " + s + " 0 0\nv " + s + " " + s + " 0\nv 0 " + s + " 0\nf 1 2 3 4\n");
    EXPECT_EQ(ReadMesh(path).n_faces(), 1u) << scale;
  }
  const std::string collinear = Write("collinear_tiny.obj",
                                      "v 0 0 0\nv 1e-150 0 0\nv 2e-150 0 0\nv 3e-150 0 0\n"
                                      "f 1 2 3 4\n");
  EXPECT_NE(InputErrorMessage([&] { ReadMesh(collinear); }).find("is degenerate"),
            std::string::npos);
}

TEST_F(MeshIoTest, DegenerateFaces) {
  const std::string collinear = Write("collinear.obj",
                                      "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n"
                                      "f 1 2 3 4\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(collinear); }),
            collinear + ":5: face 0 is degenerate: its area is zero relative to its edge lengths");

  const std::string repeated = Write("repeated.off",
                                     "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                     "3 0 1 2\n"
                                     "4 0 2 3 2\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(repeated); }),
            repeated + ":8: face 1 uses vertex 2 more than once (degenerate face)");

  const std::string two = Write("two.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 2\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(two); }),
            two + ":5: face 1 has 2 vertices; at least 3 are required");
}

TEST_F(MeshIoTest, TinyButWellShapedFaceIsNotDegenerate) {
  PolygonSoup soup = GridSoup(1, 1);
  for (Eigen::Vector3d& p : soup.vertices) p *= 1e-9;
  EXPECT_EQ(BuildMesh(soup, "tiny", {}).n_faces(), 1u);
}

TEST_F(MeshIoTest, NonManifoldEdge) {
  // Three quads hang off the edge between vertices 0 and 1.
  const std::string path = Write("fin.obj",
                                 "v 0 0 0\nv 1 0 0\n"
                                 "v 1 1 0\nv 0 1 0\n"
                                 "v 1 -1 0\nv 0 -1 0\n"
                                 "v 1 0 1\nv 0 0 1\n"
                                 "f 1 2 3 4\n"
                                 "f 2 1 6 5\n"
                                 "f 1 2 7 8\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }),
            path +
                ":11: face 2 uses the edge between vertices 0 and 1, which faces 0 and 1 "
                "already share (non-manifold edge)");
}

TEST_F(MeshIoTest, InconsistentOrientation) {
  const std::string path = Write("flipped.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                                 "f 1 2 3 4\n"
                                 "f 2 3 6 5\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }),
            path +
                ":8: face 1 traverses the edge from vertex 1 to vertex 2 in the same direction "
                "as face 0 (inconsistent orientation)");
}

TEST_F(MeshIoTest, NonManifoldVertexRejectedByOpenMesh) {
  // The centre vertex 4 of a 2 × 2 grid is interior; a triangle touching only it cannot join.
  PolygonSoup soup = GridSoup(2, 2);
  soup.vertices.emplace_back(1.0, 1.0, 1.0);
  soup.vertices.emplace_back(1.0, 1.5, 1.0);
  soup.faces.push_back({4, 9, 10});
  soup.face_lines = {10, 11, 12, 13, 14};
  EXPECT_EQ(InputErrorMessage([&] { BuildMesh(soup, "fan.obj", {}); }),
            "fan.obj:14: face 4 cannot join the mesh: one of its vertices would become "
            "non-manifold");
}

TEST_F(MeshIoTest, SoupWithoutLineNumbersOrFaces) {
  PolygonSoup soup = GridSoup(1, 1);
  soup.faces[0][2] = 7;
  EXPECT_EQ(InputErrorMessage([&] { BuildMesh(soup, "soup", {}); }),
            "soup: face 0 references vertex 7, but the mesh has 4 vertices");
  soup.faces.clear();
  EXPECT_EQ(InputErrorMessage([&] { BuildMesh(soup, "soup", {}); }), "soup: the mesh has no faces");
}

TEST_F(MeshIoTest, PlyNonManifoldEdgeAndRepeatedVertexAreReportedWithTheirLines) {
  const std::string path = Write("fin.ply",
                                 "ply\nformat ascii 1.0\n"
                                 "element vertex 8\n"
                                 "property double x\nproperty double y\nproperty double z\n"
                                 "element face 3\nproperty list uchar int vertex_indices\n"
                                 "end_header\n"
                                 "0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 -1 0\n0 -1 0\n1 0 1\n0 0 1\n"
                                 "4 0 1 2 3\n4 1 0 5 4\n4 0 1 6 7\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(path); }),
            path +
                ":20: face 2 uses the edge between vertices 0 and 1, which faces 0 and 1 "
                "already share (non-manifold edge)");

  const std::string repeated = Write("repeated.ply",
                                     "ply\nformat ascii 1.0\n"
                                     "element vertex 3\n"
                                     "property double x\nproperty double y\nproperty double z\n"
                                     "element face 2\nproperty list uchar int vertex_indices\n"
                                     "end_header\n"
                                     "0 0 0\n1 0 0\n0 1 0\n"
                                     "3 0 1 2\n3 0 1 1\n");
  EXPECT_EQ(InputErrorMessage([&] { ReadMesh(repeated); }),
            repeated + ":14: face 1 uses vertex 1 more than once (degenerate face)");
}

// ---------------------------------------------------------------------------------------------
// Writing errors.

TEST_F(MeshIoTest, WriteIntoMissingDirectoryLeavesNothingBehind) {
  const PolyMesh mesh = BuildMesh(GridSoup(2, 2), "grid", {});
  const std::string path = Path("no/such/dir/out.obj");
  const std::string message = InputErrorMessage([&] { WriteMeshAtomically(mesh, path); });
  EXPECT_THAT(message, StartsWith(path + ": cannot create the temporary file"));
  EXPECT_THAT(message, HasSubstr("No such file or directory"));
  EXPECT_TRUE(DirectoryEntries().empty());

  const std::string text = Path("no/report.txt");
  EXPECT_THAT(InputErrorMessage([&] { WriteTextFileAtomically(text, "x"); }),
              StartsWith(text + ": cannot create the temporary file"));
  EXPECT_TRUE(DirectoryEntries().empty());
}

TEST_F(MeshIoTest, FailedRenameRemovesTheTemporary) {
  // The target is a directory, so the final rename fails after the temporary was written.
  fs::create_directory(Path("out.obj"));
  const PolyMesh mesh = BuildMesh(GridSoup(2, 2), "grid", {});
  const std::string message =
      InputErrorMessage([&] { WriteMeshAtomically(mesh, Path("out.obj")); });
  EXPECT_THAT(message, StartsWith(Path("out.obj") + ": cannot move the temporary file"));
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"out.obj"});
  EXPECT_TRUE(fs::is_empty(Path("out.obj")));
}

TEST_F(MeshIoTest, NonFiniteCoordinateIsRefusedBeforeWriting) {
  const std::string path = Write("out.off", "previous\n");
  PolyMesh mesh = BuildMesh(GridSoup(2, 2), "grid", {});
  mesh.point(mesh.vertex_handle(3))[1] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(InputErrorMessage([&] { WriteMeshAtomically(mesh, path); }),
            path + ": vertex 3 has a non-finite coordinate; nothing written");
  EXPECT_EQ(ReadText(path), "previous\n");
  EXPECT_EQ(DirectoryEntries(), std::vector<std::string>{"out.off"});
}

}  // namespace
}  // namespace gproj
