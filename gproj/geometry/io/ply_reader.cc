// PLY (ASCII, binary little and big endian), read and validated here: the header names its
// line in every message, counts are checked against the file size and the memory before
// anything is allocated, and the body names the element (and, for ASCII, the line).
//
// Supported: element "vertex" with scalar properties x, y, z; element "face" with a list
// property "vertex_indices" (or "vertex_index") of integers, at least 3 per face; any other
// element or property is skipped by its declared type. Types: char/int8, uchar/uint8,
// short/int16, ushort/uint16, int/int32, uint/uint32, float/float32, double/float64. In ASCII,
// one token per value, records may span lines, and nothing may follow the last element; in
// binary, bytes after the last element are ignored.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "gproj/geometry/io/internal/mesh_text.h"

namespace gproj {
namespace mesh_io_internal {

namespace {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct PlyTypeInfo {
  const char* names[2];
  PlyType type;
  int size;
  bool integer;
  double min, max;
};

constexpr PlyTypeInfo kPlyTypes[] = {
    {{"char", "int8"}, PlyType::kInt8, 1, true, -128.0, 127.0},
    {{"uchar", "uint8"}, PlyType::kUint8, 1, true, 0.0, 255.0},
    {{"short", "int16"}, PlyType::kInt16, 2, true, -32768.0, 32767.0},
    {{"ushort", "uint16"}, PlyType::kUint16, 2, true, 0.0, 65535.0},
    {{"int", "int32"}, PlyType::kInt32, 4, true, -2147483648.0, 2147483647.0},
    {{"uint", "uint32"}, PlyType::kUint32, 4, true, 0.0, 4294967295.0},
    {{"float", "float32"}, PlyType::kFloat32, 4, false, 0.0, 0.0},
    {{"double", "float64"}, PlyType::kFloat64, 8, false, 0.0, 0.0},
};

const PlyTypeInfo& Info(PlyType type) { return kPlyTypes[static_cast<int>(type)]; }

bool ParsePlyType(std::string_view name, PlyType* type) {
  for (const PlyTypeInfo& info : kPlyTypes) {
    if (name == info.names[0] || name == info.names[1]) {
      *type = info.type;
      return true;
    }
  }
  return false;
}

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  // lists only
  PlyType type = PlyType::kFloat32;      // the value, or each item of a list
};

struct PlyElement {
  std::string name;
  long long count = 0;
  int line = 0;  // of its "element" line
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  bool has_format = false;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;  // first byte after the "end_header" line
  int body_line = 0;            // line number of that byte
};

// ---------------------------------------------------------------------------------------------
// Header.

void ParseFormatLine(const std::string& path, int line, const std::vector<std::string_view>& w,
                     PlyHeader* header) {
  if (header->has_format) Fail(path, line, "a second \"format\" line");
  if (w.size() != 3) {
    Fail(path, line, "expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
  }
  if (w[1] == "ascii") {
    header->format = PlyFormat::kAscii;
  } else if (w[1] == "binary_little_endian") {
    header->format = PlyFormat::kBinaryLittleEndian;
  } else if (w[1] == "binary_big_endian") {
    header->format = PlyFormat::kBinaryBigEndian;
  } else {
    Fail(path, line, "unknown PLY format " + Quote(w[1]));
  }
  double version = 0.0;
  if (!ParseDouble(w[2], &version) || version != 1.0) {
    Fail(path, line, "unsupported PLY version " + Quote(w[2]) + "; expected 1.0");
  }
  header->has_format = true;
}

void ParseElementLine(const std::string& path, int line, const std::vector<std::string_view>& w,
                      PlyHeader* header) {
  if (w.size() != 3) Fail(path, line, "expected \"element NAME COUNT\"");
  for (const PlyElement& element : header->elements) {
    if (element.name == w[1]) Fail(path, line, "a second element " + Quote(w[1]));
  }
  long long count = 0;
  if (!ParseInt(w[2], &count) || count < 0) {
    Fail(path, line, "malformed element count " + Quote(w[2]));
  }
  if (count > std::numeric_limits<int>::max()) {
    Fail(path, line,
         "element " + std::string(w[1]) + " declares " + std::to_string(count) +
             " items; at most " + std::to_string(std::numeric_limits<int>::max()) +
             " are supported");
  }
  header->elements.push_back({std::string(w[1]), count, line, {}});
}

void ParsePropertyLine(const std::string& path, int line, const std::vector<std::string_view>& w,
                       PlyHeader* header) {
  if (header->elements.empty()) {
    Fail(path, line, "a \"property\" line before any \"element\" line");
  }
  PlyProperty property;
  const bool is_list = w.size() >= 2 && w[1] == "list";
  if (is_list ? w.size() != 5 : w.size() != 3) {
    Fail(path, line, "expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\"");
  }
  property.is_list = is_list;
  const std::string_view type = is_list ? w[3] : w[1];
  if (!ParsePlyType(type, &property.type)) {
    Fail(path, line, "unknown property type " + Quote(type));
  }
  if (is_list &&
      (!ParsePlyType(w[2], &property.count_type) || !Info(property.count_type).integer)) {
    Fail(path, line, "a list's count type must be an integer type, not " + Quote(w[2]));
  }
  property.name = std::string(w.back());
  PlyElement& element = header->elements.back();
  for (const PlyProperty& other : element.properties) {
    if (other.name == property.name) {
      Fail(path, line, "element " + element.name + " has a second property " + Quote(w.back()));
    }
  }
  element.properties.push_back(std::move(property));
}

// Parses one header line; true at "end_header".
bool ParseHeaderLine(const std::string& path, int line, std::string_view text, PlyHeader* header) {
  const std::vector<std::string_view> w = Tokens(text);
  if (line == 1) {
    if (w.size() != 1 || w[0] != "ply")
      Fail(path, 1, "not a PLY file: the first line is not \"ply\"");
    return false;
  }
  if (w.empty()) return false;
  if (w[0] == "end_header") {
    if (w.size() != 1) Fail(path, line, "expected \"end_header\" alone on its line");
    return true;
  }
  if (w[0] == "format") {
    ParseFormatLine(path, line, w, header);
  } else if (w[0] == "element") {
    ParseElementLine(path, line, w, header);
  } else if (w[0] == "property") {
    ParsePropertyLine(path, line, w, header);
  } else if (w[0] != "comment" && w[0] != "obj_info") {
    Fail(path, line, "unknown PLY header keyword " + Quote(w[0]));
  }
  return false;
}

PlyHeader ParsePlyHeader(const std::string& path, std::string_view data) {
  PlyHeader header;
  std::size_t pos = 0;
  for (int line = 1; pos < data.size(); ++line) {
    std::size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) end = data.size();
    const std::string_view text = data.substr(pos, end - pos);
    pos = std::min(end + 1, data.size());
    if (ParseHeaderLine(path, line, text, &header)) {
      if (!header.has_format) Fail(path, line, "the PLY header has no \"format\" line");
      header.body_offset = pos;
      header.body_line = line + 1;
      return header;
    }
  }
  Fail(path, 0, "the PLY header has no \"end_header\" line");
}

// ---------------------------------------------------------------------------------------------
// The elements gproj reads, and the size checks.

struct PlyLayout {
  int vertex = -1, face = -1;  // element indices
  int x = -1, y = -1, z = -1;  // property indices in the vertex element
  int indices = -1;            // property index in the face element
};

int FindProperty(const PlyElement& element, std::string_view name) {
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    if (element.properties[p].name == name) return static_cast<int>(p);
  }
  return -1;
}

int FindScalar(const std::string& path, const PlyElement& vertex, const char* name) {
  const int p = FindProperty(vertex, name);
  if (p < 0) Fail(path, vertex.line, std::string("element vertex has no property ") + name);
  if (vertex.properties[p].is_list) {
    Fail(path, vertex.line, std::string("property ") + name + " of element vertex is a list");
  }
  return p;
}

PlyLayout FindLayout(const std::string& path, const PlyHeader& header) {
  PlyLayout layout;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    if (header.elements[e].name == "vertex") layout.vertex = static_cast<int>(e);
    if (header.elements[e].name == "face") layout.face = static_cast<int>(e);
  }
  if (layout.face < 0 || header.elements[layout.face].count == 0) {
    Fail(path, 0, "the file has no faces");
  }
  if (layout.vertex < 0) Fail(path, 0, "the PLY header has no \"element vertex\" line");
  const PlyElement& vertex = header.elements[layout.vertex];
  layout.x = FindScalar(path, vertex, "x");
  layout.y = FindScalar(path, vertex, "y");
  layout.z = FindScalar(path, vertex, "z");
  const PlyElement& face = header.elements[layout.face];
  layout.indices = FindProperty(face, "vertex_indices");
  if (layout.indices < 0) layout.indices = FindProperty(face, "vertex_index");
  if (layout.indices < 0) {
    Fail(path, face.line, "element face has no property vertex_indices (or vertex_index)");
  }
  const PlyProperty& indices = face.properties[layout.indices];
  if (!indices.is_list || !Info(indices.type).integer) {
    Fail(path, face.line,
         "property " + indices.name + " of element face must be a list of integers");
  }
  return layout;
}

// Fewest bytes (binary) or tokens (ASCII) of one item of an element.
double MinimalItemSize(const PlyElement& element, bool binary, int indices) {
  double size = 0.0;
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    const int min_items = static_cast<int>(p) == indices ? 3 : 0;
    if (!property.is_list) {
      size += binary ? Info(property.type).size : 1;
    } else {
      size += binary ? Info(property.count_type).size + min_items * Info(property.type).size
                     : 1 + min_items;
    }
  }
  return size;
}

std::string ItemsName(const PlyElement& element) {
  if (element.name == "vertex") return "vertices";
  if (element.name == "face") return "faces";
  return "items";
}

void CheckPlySizes(const std::string& path, const PlyHeader& header, const PlyLayout& layout,
                   std::size_t available) {
  const bool binary = header.format != PlyFormat::kAscii;
  double needed = 0.0;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    const int indices = static_cast<int>(e) == layout.face ? layout.indices : -1;
    needed += static_cast<double>(element.count) * MinimalItemSize(element, binary, indices);
    const std::string what = "element " + element.name + " declares " +
                             std::to_string(element.count) + " " + ItemsName(element) +
                             (e > 0 ? " (after the elements before it)" : "");
    if (binary && needed > static_cast<double>(available)) {
      Fail(path, element.line,
           what + ", which need at least " + ByteCount(needed) + ", but the file has only " +
               ByteCount(static_cast<double>(available)) + " after the header");
    }
    if (!binary) CheckTokensFit(path, element.line, what, needed, available, "after the header");
  }
  const double vertices = static_cast<double>(header.elements[layout.vertex].count);
  const double faces = static_cast<double>(header.elements[layout.face].count);
  CheckMemory(path, header.elements[layout.face].line,
              "reading " + std::to_string(header.elements[layout.vertex].count) + " vertices and " +
                  std::to_string(header.elements[layout.face].count) + " faces",
              MeshMemoryEstimate(vertices, faces, 3.0 * faces));
}

// ---------------------------------------------------------------------------------------------
// Body: the values of ASCII tokens or binary bytes, through one interface.

// Where a value is read, for messages: "<path>:<line>: vertex 3" / "<path>: face 7".
struct PlyPlace {
  const std::string& path;
  const PlyElement& element;
  long long item;

  std::string Name() const {
    const bool known = element.name == "vertex" || element.name == "face";
    return (known ? element.name : "element " + element.name) + " " + std::to_string(item);
  }
};

class PlyAsciiValues {
 public:
  explicit PlyAsciiValues(std::string_view body, int first_line)
      : reader_(body, /*hash_comments=*/false), first_line_(first_line) {}

  // The next value of `type`, range-checked for integer types.
  double Read(PlyType type, const PlyPlace& place) {
    Token token;
    if (!reader_.Next(&token)) {
      Fail(place.path, 0,
           "the file ends in " + place.Name() + " of " + std::to_string(place.element.count) +
               " (element " + place.element.name + ")");
    }
    line_ = token.line + first_line_ - 1;
    const PlyTypeInfo& info = Info(type);
    long long integer = 0;
    double value = 0.0;
    if (info.integer) {
      if (!ParseInt(token.text, &integer) || integer < info.min || integer > info.max) {
        Fail(place.path, line_,
             place.Name() + " has " + Quote(token.text) + " where a " + info.names[0] +
                 " is declared");
      }
      return static_cast<double>(integer);
    }
    if (!ParseDouble(token.text, &value)) {
      Fail(place.path, line_, place.Name() + " has a malformed number " + Quote(token.text));
    }
    return value;
  }

  // Line of the last value read, and of the next one.
  int line() const { return line_; }
  int NextLine() const {
    TokenReader ahead = reader_;
    Token token;
    return ahead.Next(&token) ? token.line + first_line_ - 1 : 0;
  }

  void CheckEnd(const std::string& path) {
    Token token;
    if (reader_.Next(&token)) {
      Fail(path, token.line + first_line_ - 1,
           "unexpected " + Quote(token.text) + " after the last element");
    }
  }

 private:
  TokenReader reader_;
  int first_line_;
  int line_ = 0;
};

class PlyBinaryValues {
 public:
  PlyBinaryValues(std::string_view body, bool big_endian) : body_(body), big_endian_(big_endian) {}

  double Read(PlyType type, const PlyPlace& place) {
    const int size = Info(type).size;
    if (body_.size() - pos_ < static_cast<std::size_t>(size)) {
      Fail(place.path, 0,
           "the file ends in " + place.Name() + " of " + std::to_string(place.element.count) +
               " (element " + place.element.name + ")");
    }
    unsigned char bytes[8];
    std::memcpy(bytes, body_.data() + pos_, size);
    pos_ += size;
    if (big_endian_ != HostIsBigEndian()) std::reverse(bytes, bytes + size);
    return Decode(type, bytes);
  }

  int line() const { return 0; }
  int NextLine() const { return 0; }
  void CheckEnd(const std::string&) {}

 private:
  static bool HostIsBigEndian() {
    const std::uint16_t one = 1;
    unsigned char first = 0;
    std::memcpy(&first, &one, 1);
    return first == 0;
  }
  static double Decode(PlyType type, const unsigned char* bytes) {
    switch (type) {
      case PlyType::kInt8:
        return Load<std::int8_t>(bytes);
      case PlyType::kUint8:
        return Load<std::uint8_t>(bytes);
      case PlyType::kInt16:
        return Load<std::int16_t>(bytes);
      case PlyType::kUint16:
        return Load<std::uint16_t>(bytes);
      case PlyType::kInt32:
        return Load<std::int32_t>(bytes);
      case PlyType::kUint32:
        return Load<std::uint32_t>(bytes);
      case PlyType::kFloat32:
        return Load<float>(bytes);
      case PlyType::kFloat64:
        return Load<double>(bytes);
    }
    return 0.0;
  }
  template <class T>
  static double Load(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return static_cast<double>(value);
  }

  std::string_view body_;
  bool big_endian_;
  std::size_t pos_ = 0;
};

// A list's length, non-negative.
template <class Values>
long long ReadListLength(Values* values, const PlyProperty& property, const PlyPlace& place) {
  const double length = values->Read(property.count_type, place);
  if (length < 0) {
    Fail(place.path, values->line(),
         place.Name() + " has a negative length for the list " + property.name);
  }
  return static_cast<long long>(length);
}

template <class Values>
void SkipProperty(Values* values, const PlyProperty& property, const PlyPlace& place) {
  if (!property.is_list) {
    values->Read(property.type, place);
    return;
  }
  const long long length = ReadListLength(values, property, place);
  for (long long i = 0; i < length; ++i) values->Read(property.type, place);
}

template <class Values>
void ReadVertex(Values* values, const PlyElement& element, const PlyLayout& layout,
                const PlyPlace& place, PolygonSoup* soup) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  const int line = values->NextLine();
  for (int k = 0; k < static_cast<int>(element.properties.size()); ++k) {
    const PlyProperty& property = element.properties[k];
    const int axis = k == layout.x ? 0 : k == layout.y ? 1 : k == layout.z ? 2 : -1;
    if (axis < 0) {
      SkipProperty(values, property, place);
      continue;
    }
    p[axis] = values->Read(property.type, place);
    if (!std::isfinite(p[axis])) {
      Fail(place.path, values->line(),
           place.Name() + " has a non-finite coordinate " + property.name);
    }
  }
  soup->vertices.push_back(p);
  soup->vertex_lines.push_back(line);
}

template <class Values>
std::vector<int> ReadFaceIndices(Values* values, const PlyProperty& property, const PlyPlace& place,
                                 int num_vertices) {
  const long long length = ReadListLength(values, property, place);
  if (length < 3) {
    Fail(place.path, values->line(),
         place.Name() + " has " + std::to_string(length) + (length == 1 ? " vertex" : " vertices") +
             "; at least 3 are required");
  }
  std::vector<int> face;
  for (long long i = 0; i < length; ++i) {
    const double index = values->Read(property.type, place);
    if (index < 0 || index >= num_vertices) {
      Fail(place.path, values->line(),
           place.Name() + " references vertex " + std::to_string(static_cast<long long>(index)) +
               ", but the file has " + std::to_string(num_vertices) + " vertices");
    }
    face.push_back(static_cast<int>(index));
  }
  return face;
}

template <class Values>
void ReadFace(Values* values, const PlyElement& element, const PlyLayout& layout,
              const PlyPlace& place, int num_vertices, PolygonSoup* soup) {
  std::vector<int> face;
  const int line = values->NextLine();
  for (int k = 0; k < static_cast<int>(element.properties.size()); ++k) {
    if (k == layout.indices) {
      face = ReadFaceIndices(values, element.properties[k], place, num_vertices);
    } else {
      SkipProperty(values, element.properties[k], place);
    }
  }
  soup->faces.push_back(std::move(face));
  soup->face_lines.push_back(line);
}

template <class Values>
PolygonSoup ReadBody(const std::string& path, const PlyHeader& header, const PlyLayout& layout,
                     Values* values) {
  PolygonSoup soup;
  const int num_vertices = static_cast<int>(header.elements[layout.vertex].count);
  const int num_faces = static_cast<int>(header.elements[layout.face].count);
  soup.vertices.reserve(num_vertices);
  soup.vertex_lines.reserve(num_vertices);
  soup.faces.reserve(num_faces);
  soup.face_lines.reserve(num_faces);
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    if (element.properties.empty()) continue;  // nothing to read, however many
    for (long long item = 0; item < element.count; ++item) {
      const PlyPlace place{path, element, item};
      if (static_cast<int>(e) == layout.vertex) {
        ReadVertex(values, element, layout, place, &soup);
      } else if (static_cast<int>(e) == layout.face) {
        ReadFace(values, element, layout, place, num_vertices, &soup);
      } else {
        for (const PlyProperty& property : element.properties) {
          SkipProperty(values, property, place);
        }
      }
    }
  }
  values->CheckEnd(path);
  return soup;
}

}  // namespace

PolygonSoup ReadPly(const std::string& path, std::string_view data) {
  if (data.empty()) Fail(path, 0, "the file is empty");
  const PlyHeader header = ParsePlyHeader(path, data);
  const PlyLayout layout = FindLayout(path, header);
  const std::string_view body = data.substr(header.body_offset);
  CheckPlySizes(path, header, layout, body.size());
  if (header.format == PlyFormat::kAscii) {
    PlyAsciiValues values(body, header.body_line);
    return ReadBody(path, header, layout, &values);
  }
  PlyBinaryValues values(body, header.format == PlyFormat::kBinaryBigEndian);
  return ReadBody(path, header, layout, &values);
}

}  // namespace mesh_io_internal
}  // namespace gproj
