#include "inputs/mesh_reader.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace rockbake {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
  throw std::runtime_error(fmt::format("cannot read mesh {}: {}", file.string(), problem));
}

std::string readAll(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "no such file, or it cannot be opened");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void addPolygon(TriangleMesh& mesh, const std::vector<std::uint32_t>& polygon, const std::filesystem::path& file,
                std::size_t line) {
  if (polygon.size() < 3) fail(file, fmt::format("line {}: a face needs at least 3 vertices", line));
  for (std::uint32_t v : polygon)
    if (v >= mesh.positions.size())
      fail(file, fmt::format("line {}: vertex index {} past the {} vertices", line, v + 1, mesh.positions.size()));
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
    mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
}

TriangleMesh readObj(const std::filesystem::path& file, const std::string& text) {
  TriangleMesh mesh;
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  std::vector<std::uint32_t> polygon;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      std::array<double, 3> p;
      if (!(words >> p[0] >> p[1] >> p[2])) fail(file, fmt::format("line {}: a vertex needs x y z", number));
      mesh.positions.push_back(p);
    } else if (tag == "f") {
      polygon.clear();
      for (std::string corner; words >> corner;) {
        long index = 0;
        try {
          index = std::stol(corner.substr(0, corner.find('/')));
        } catch (const std::exception&) {
          fail(file, fmt::format("line {}: '{}' is not a vertex index", number, corner));
        }
        // Negative indices count back from the last vertex.
        const long resolved = index < 0 ? long(mesh.positions.size()) + index : index - 1;
        if (resolved < 0) fail(file, fmt::format("line {}: vertex index {} is out of range", number, index));
        polygon.push_back(std::uint32_t(resolved));
      }
      addPolygon(mesh, polygon, file, number);
    }
  }
  return mesh;
}

// Binary STL repeats each corner per triangle; shared corners are merged by position.
std::uint32_t vertexOf(TriangleMesh& mesh, std::map<std::array<double, 3>, std::uint32_t>& index,
                       const std::array<double, 3>& p) {
  const auto [it, inserted] = index.emplace(p, std::uint32_t(mesh.positions.size()));
  if (inserted) mesh.positions.push_back(p);
  return it->second;
}

TriangleMesh readStl(const std::filesystem::path& file, const std::string& bytes) {
  TriangleMesh mesh;
  std::map<std::array<double, 3>, std::uint32_t> index;
  const bool ascii = bytes.rfind("solid", 0) == 0 && bytes.find("facet") != std::string::npos;
  if (ascii) {
    std::istringstream in(bytes);
    std::string word;
    std::array<std::uint32_t, 3> triangle{};
    int corner = 0;
    while (in >> word) {
      if (word != "vertex") continue;
      std::array<double, 3> p;
      if (!(in >> p[0] >> p[1] >> p[2])) fail(file, "a vertex needs x y z");
      triangle[std::size_t(corner++)] = vertexOf(mesh, index, p);
      if (corner == 3) mesh.triangles.push_back(triangle), corner = 0;
    }
    return mesh;
  }
  if (bytes.size() < 84) fail(file, "too short for a binary STL");
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  if (bytes.size() < 84 + std::size_t(count) * 50)
    fail(file, fmt::format("binary STL says {} triangles but holds fewer", count));
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + 84 + std::size_t(t) * 50 + 12;  // skip the normal
    std::array<std::uint32_t, 3> triangle;
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, record + 12 * c, 12);
      triangle[std::size_t(c)] = vertexOf(mesh, index, {xyz[0], xyz[1], xyz[2]});
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

TriangleMesh readPly(const std::filesystem::path& file, const std::string& bytes) {
  const std::size_t header_end = bytes.find("end_header");
  if (bytes.rfind("ply", 0) != 0 || header_end == std::string::npos) fail(file, "not a PLY file (no ply header)");
  std::istringstream header(bytes.substr(0, header_end));
  std::string line, format, element;
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> vertex_types, vertex_names;
  std::string face_count_type, face_index_type;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "format") {
      words >> format;
    } else if (tag == "element") {
      std::size_t n = 0;
      words >> element >> n;
      (element == "vertex" ? vertices : element == "face" ? faces : n) = n;
    } else if (tag == "property" && element == "vertex") {
      std::string type, name;
      words >> type >> name;
      vertex_types.push_back(type);
      vertex_names.push_back(name);
    } else if (tag == "property" && element == "face") {
      std::string list;
      words >> list >> face_count_type >> face_index_type;
    }
  }
  if (format != "ascii" && format != "binary_little_endian")
    fail(file, "PLY format '" + format + "' is not supported (ascii or binary_little_endian)");
  const auto axis = [&](const char* name) -> std::ptrdiff_t {
    const auto it = std::find(vertex_names.begin(), vertex_names.end(), name);
    if (it == vertex_names.end()) fail(file, fmt::format("vertices have no '{}' property", name));
    return it - vertex_names.begin();
  };
  const std::ptrdiff_t ax = axis("x"), ay = axis("y"), az = axis("z");
  std::size_t body = bytes.find('\n', header_end) + 1;
  TriangleMesh mesh;
  mesh.positions.reserve(vertices);
  std::vector<std::uint32_t> polygon;

  if (format == "ascii") {
    std::istringstream in(bytes.substr(body));
    for (std::size_t v = 0; v < vertices; ++v) {
      std::vector<double> values(vertex_names.size());
      for (double& x : values)
        if (!(in >> x)) fail(file, fmt::format("vertex {} is incomplete", v));
      mesh.positions.push_back({values[std::size_t(ax)], values[std::size_t(ay)], values[std::size_t(az)]});
    }
    for (std::size_t f = 0; f < faces; ++f) {
      std::size_t n = 0;
      if (!(in >> n)) fail(file, fmt::format("face {} is incomplete", f));
      polygon.assign(n, 0);
      for (auto& i : polygon)
        if (!(in >> i)) fail(file, fmt::format("face {} is incomplete", f));
      addPolygon(mesh, polygon, file, f);
    }
    return mesh;
  }

  const auto size_of = [&](const std::string& type) -> std::size_t {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
      return 4;
    if (type == "double" || type == "float64") return 8;
    fail(file, "unknown PLY type '" + type + "'");
  };
  const auto read_value = [&](const std::string& type, std::size_t& at) -> double {
    const std::size_t n = size_of(type);
    if (at + n > bytes.size()) fail(file, "the binary data is shorter than the header says");
    const char* p = bytes.data() + at;
    at += n;
    // memcpy: the values sit at any byte offset, and a cast pointer would read them unaligned.
    if (type == "float" || type == "float32") {
      float v;
      std::memcpy(&v, p, 4);
      return double(v);
    }
    if (type == "double" || type == "float64") {
      double v;
      std::memcpy(&v, p, 8);
      return v;
    }
    if (n == 1) return type[0] == 'u' ? double(std::uint8_t(*p)) : double(std::int8_t(*p));
    if (n == 2) {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return type[0] == 'u' ? double(v) : double(std::int16_t(v));
    }
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return type[0] == 'u' ? double(v) : double(std::int32_t(v));
  };
  for (std::size_t v = 0; v < vertices; ++v) {
    std::array<double, 3> p{};
    for (std::size_t k = 0; k < vertex_types.size(); ++k) {
      const double value = read_value(vertex_types[k], body);
      if (std::ptrdiff_t(k) == ax) p[0] = value;
      if (std::ptrdiff_t(k) == ay) p[1] = value;
      if (std::ptrdiff_t(k) == az) p[2] = value;
    }
    mesh.positions.push_back(p);
  }
  for (std::size_t f = 0; f < faces; ++f) {
    polygon.assign(std::size_t(read_value(face_count_type, body)), 0);
    for (auto& i : polygon) i = std::uint32_t(read_value(face_index_type, body));
    addPolygon(mesh, polygon, file, f);
  }
  return mesh;
}

}  // namespace

TriangleMesh readTriangleMesh(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const std::string bytes = readAll(file);
  TriangleMesh mesh;
  if (extension == ".obj")
    mesh = readObj(file, bytes);
  else if (extension == ".ply")
    mesh = readPly(file, bytes);
  else if (extension == ".stl")
    mesh = readStl(file, bytes);
  else
    fail(file, "unknown extension '" + extension + "' (use .obj, .ply or .stl)");
  if (mesh.triangles.empty()) fail(file, "it has no faces");
  return mesh;
}

}  // namespace rockbake
