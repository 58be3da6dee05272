#include "python/extension/conversions.h"

#include <pybind11/stl.h>

#include <climits>
#include <cmath>

#include "gproj/common/input_error.h"

namespace gproj::python {

namespace {

// The name of an array's dtype, e.g. "complex128".
std::string DtypeName(const py::array& array) { return py::str(array.dtype()).cast<std::string>(); }

// The library's message for a face index outside the vertices (gproj/geometry/io/mesh_io.cc).
[[noreturn]] void IndexOutOfRange(std::size_t face, long long index, std::size_t num_vertices) {
  throw InputError("mesh: face " + std::to_string(face) + " references vertex " +
                   std::to_string(index) + ", but the mesh has " + std::to_string(num_vertices) +
                   " vertices");
}

int ToIndex(long long value, std::size_t face, std::size_t num_vertices) {
  if (value < INT_MIN || value > INT_MAX) IndexOutOfRange(face, value, num_vertices);
  return static_cast<int>(value);
}

// Faces of an (m, k) integer array.
std::vector<std::vector<int>> FacesFromArray(const py::array& array, const std::string& name,
                                             std::size_t num_vertices) {
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw InputError(name + " must hold integer vertex indices, got dtype " + DtypeName(array));
  if (array.ndim() != 2)
    throw InputError(name + " must be an (m, k) array of vertex indices, got shape " +
                     ShapeText(array));
  const auto indices = py::array_t<long long, py::array::c_style | py::array::forcecast>(array);
  const auto view = indices.unchecked<2>();
  std::vector<std::vector<int>> faces(view.shape(0), std::vector<int>(view.shape(1)));
  for (py::ssize_t f = 0; f < view.shape(0); ++f)
    for (py::ssize_t k = 0; k < view.shape(1); ++k)
      faces[f][k] = ToIndex(view(f, k), f, num_vertices);
  return faces;
}

// Faces of a sequence of sequences of integers (faces of any size).
std::vector<std::vector<int>> FacesFromSequence(const py::handle& faces, const std::string& name,
                                                std::size_t num_vertices) {
  if (!py::isinstance<py::sequence>(faces) || py::isinstance<py::str>(faces))
    throw InputError(name + " must be an (m, k) integer array or a list of faces, got " +
                     py::str(faces.get_type().attr("__name__")).cast<std::string>());
  std::vector<std::vector<int>> result;
  const auto sequence = py::reinterpret_borrow<py::sequence>(faces);
  for (std::size_t f = 0; f < sequence.size(); ++f) {
    const py::object face = sequence[f];
    if (!py::isinstance<py::sequence>(face) || py::isinstance<py::str>(face))
      throw InputError(name + ": face " + std::to_string(f) + " is not a list of vertex indices");
    std::vector<int>& indices = result.emplace_back();
    for (const py::handle index : face) {
      if (!PyIndex_Check(index.ptr()) || PyBool_Check(index.ptr()))
        throw InputError(name + ": face " + std::to_string(f) + " has " +
                         py::repr(index).cast<std::string>() + ", not an integer vertex index");
      int overflow = 0;
      const py::int_ value = py::reinterpret_steal<py::int_>(PyNumber_Index(index.ptr()));
      const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
      if (overflow != 0) IndexOutOfRange(f, overflow > 0 ? LLONG_MAX : LLONG_MIN, num_vertices);
      indices.push_back(ToIndex(v, f, num_vertices));
    }
  }
  return result;
}

std::vector<std::vector<int>> FacesFrom(const py::handle& faces, const std::string& name,
                                        std::size_t num_vertices) {
  if (py::isinstance<py::array>(faces))
    return FacesFromArray(py::reinterpret_borrow<py::array>(faces), name, num_vertices);
  return FacesFromSequence(faces, name, num_vertices);
}

}  // namespace

std::string ShapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d)
    text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

std::vector<Eigen::Vector3d> PointsFromArray(const py::handle& value, const std::string& name) {
  const py::array array = py::array::ensure(value);
  if (!array) throw InputError(name + " must be an (n, 3) array of floats");
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw InputError(name + " must be an (n, 3) array of floats, got dtype " + DtypeName(array));
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw InputError(name + " must be an (n, 3) array of floats, got shape " + ShapeText(array));
  const auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>(array);
  const auto view = doubles.unchecked<2>();
  std::vector<Eigen::Vector3d> points(view.shape(0));
  for (py::ssize_t i = 0; i < view.shape(0); ++i)
    points[i] = Eigen::Vector3d(view(i, 0), view(i, 1), view(i, 2));
  return points;
}

std::vector<std::vector<int>> FacesFromPython(const py::handle& faces, const std::string& name) {
  return FacesFrom(faces, name, 0);
}

PolyMesh MeshFromArrays(const py::handle& vertices, const py::handle& faces,
                        const MeshRequirements& requirements, std::vector<int>* weld_map) {
  PolygonSoup soup;
  soup.vertices = PointsFromArray(vertices, "V");
  soup.faces = FacesFrom(faces, "F", soup.vertices.size());
  return BuildMesh(soup, "mesh", requirements, weld_map);
}

py::array_t<double> VerticesToArray(const PolyMesh& mesh) {
  py::array_t<double> array({static_cast<py::ssize_t>(mesh.n_vertices()), py::ssize_t{3}});
  auto view = array.mutable_unchecked<2>();
  for (const auto vh : mesh.vertices())
    for (int c = 0; c < 3; ++c) view(vh.idx(), c) = mesh.point(vh)[c];
  return array;
}

py::object FacesToPython(const PolyMesh& mesh) {
  std::vector<std::vector<int>> faces;
  faces.reserve(mesh.n_faces());
  for (const auto fh : mesh.faces()) {
    std::vector<int>& face = faces.emplace_back();
    for (const auto vh : mesh.fv_range(fh)) face.push_back(vh.idx());
  }
  const std::size_t k = faces.empty() ? 0 : faces[0].size();
  bool uniform = true;
  for (const auto& face : faces) uniform = uniform && face.size() == k;
  if (!uniform) return py::cast(faces);
  py::array_t<int> array({static_cast<py::ssize_t>(faces.size()), static_cast<py::ssize_t>(k)});
  auto view = array.mutable_unchecked<2>();
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::size_t j = 0; j < k; ++j) view(f, j) = faces[f][j];
  return std::move(array);
}

py::tuple MeshToPython(const PolyMesh& mesh) {
  return py::make_tuple(VerticesToArray(mesh), FacesToPython(mesh));
}

Eigen::Vector3d Vector3FromPython(const py::handle& value, const std::string& name) {
  std::vector<double> values;
  try {
    values = value.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw InputError(name + " needs three numbers");
  }
  if (values.size() != 3)
    throw InputError(name + " needs three numbers, got " + std::to_string(values.size()));
  const Eigen::Vector3d p(values[0], values[1], values[2]);
  if (!p.allFinite()) throw InputError(name + " must be finite");
  return p;
}

py::object JsonToPython(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<long long>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<unsigned long long>());
    case nlohmann::json::value_t::number_float:
      return py::float_(j.get<double>());
    case nlohmann::json::value_t::string:
      return py::str(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const auto& item : j) list.append(JsonToPython(item));
      return std::move(list);
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (auto it = j.begin(); it != j.end(); ++it) dict[py::str(it.key())] = JsonToPython(*it);
      return std::move(dict);
    }
    default:
      return py::none();
  }
}

nlohmann::json PythonToJson(const py::handle& value) {
  if (value.is_none()) return nullptr;
  // numpy arrays and scalars as Python lists and numbers.
  if (py::hasattr(value, "tolist")) return PythonToJson(value.attr("tolist")());
  if (PyBool_Check(value.ptr())) return value.cast<bool>();
  if (PyLong_Check(value.ptr())) {
    int overflow = 0;
    const long long n = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow == 0) return n;
    // Beyond 64 bits: as a number (infinite beyond a double), which the option checks refuse.
    const double d = PyLong_AsDouble(value.ptr());
    if (d == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      return overflow * HUGE_VAL;
    }
    return d;
  }
  if (PyFloat_Check(value.ptr())) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value))
      object[py::str(key).cast<std::string>()] = PythonToJson(item);
    return object;
  }
  if (py::isinstance<py::sequence>(value)) {
    nlohmann::json array = nlohmann::json::array();
    for (const py::handle item : value) array.push_back(PythonToJson(item));
    return array;
  }
  throw InputError("cannot convert a " +
                   py::str(value.get_type().attr("__name__")).cast<std::string>() + " to JSON");
}

}  // namespace gproj::python
