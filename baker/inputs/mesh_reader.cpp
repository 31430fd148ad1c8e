#include "inputs/mesh_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace rockbake {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
  throw std::runtime_error(fmt::format("cannot read mesh {}: {}", file.string(), problem));
}

// A blockout is modelled by hand; anything larger is not one, and would be read whole into memory.
constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(1) << 30;

// The size limit, and whether the file opens: what every format checks first.
// Returns the file's size.
std::uintmax_t checkReadable(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(file, ec);
  // A FIFO would be waited on, and a large OBJ is read twice.
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    fail(file, "not a regular file (a folder, a FIFO or a device)");
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!ec && size > kMaxMeshFileBytes)
    fail(file, fmt::format("the file is {} MiB; blockouts are read up to {} MiB", size >> 20, kMaxMeshFileBytes >> 20));
  if (ec) fail(file, "no such file, or it cannot be opened");
  return size;
}

std::string readAll(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "no such file, or it cannot be opened");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// NaN or infinite coordinates would pass as a vertex and break every test that follows ("not closed").
void checkFinite(const std::filesystem::path& file, const std::array<double, 3>& p, std::size_t vertex) {
  for (double c : p)
    if (!std::isfinite(c))
      fail(file,
           fmt::format("vertex {} has a coordinate that is not a finite number ({} {} {})", vertex, p[0], p[1], p[2]));
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

// The lines of a file, read through a buffer of its own: the file is never held whole, and a line longer
// than an OBJ's ever is (a binary file, a file of zeros) is refused before it is gathered.
class LineReader {
 public:
  static constexpr std::size_t kMaxLineBytes = std::size_t(1) << 20;

  explicit LineReader(const std::filesystem::path& file) : file_(file) {
    in_.open(file, std::ios::binary);
    if (!in_) fail(file, "no such file, or it cannot be opened");
  }

  // As std::getline: false at the end of the file.
  bool next(std::string& line) {
    ++number_;
    line.clear();
    for (;;) {
      in_.getline(chunk_.data(), std::streamsize(chunk_.size()));
      const auto extracted = std::size_t(in_.gcount());
      if (in_.eof()) {  // the last line, without its line feed
        line.append(chunk_.data(), extracted);
        return !line.empty();
      }
      if (!in_.fail()) {
        line.append(chunk_.data(), extracted - 1);  // without the line feed
        return true;
      }
      line.append(chunk_.data(), extracted);  // a chunk of a longer line
      if (line.size() > kMaxLineBytes)
        fail(file_, fmt::format("line {} is longer than {} KiB: not an OBJ file", number_, kMaxLineBytes >> 10));
      in_.clear();
    }
  }

 private:
  const std::filesystem::path& file_;
  std::array<char, 16384> chunk_;  // a line is gathered through it, a chunk at a time
  std::ifstream in_;
  std::size_t number_ = 0;
};

// Whitespace-separated words of a line, as operator>> splits them.
template <typename F>
void forEachWord(const std::string& line, F&& f) {
  const auto space = [](char c) { return c == ' ' || (c >= '\t' && c <= '\r'); };
  for (std::size_t i = 0; i < line.size();) {
    while (i < line.size() && space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !space(line[i])) ++i;
    if (i > start && !f(std::string_view(line).substr(start, i - start))) return;
  }
}

// How many vertices and triangles an OBJ file holds (fan-triangulated faces), from a pass over its lines.
// Worth it from this size on: below, the doubling costs less than a second pass.
constexpr std::uintmax_t kCountObjBytes = std::uintmax_t(1) << 20;

std::pair<std::size_t, std::size_t> countObj(const std::filesystem::path& file) {
  LineReader lines(file);
  std::size_t vertices = 0, triangles = 0;
  for (std::string line; lines.next(line);) {
    std::size_t words = 0;
    bool face = false;
    forEachWord(line, [&](std::string_view word) {
      if (words++ == 0) {
        vertices += word == "v";
        face = word == "f";
        return face;
      }
      return true;
    });
    if (face && words >= 4) triangles += words - 3;
  }
  return {vertices, triangles};
}

// Streamed, a line at a time: what is held is the mesh, not the file's text. A large file is counted
// first, so that the mesh is allocated once at its size rather than grown by doubling.
TriangleMesh readObj(const std::filesystem::path& file, std::uintmax_t size) {
  TriangleMesh mesh;
  if (size >= kCountObjBytes) {
    const auto [vertices, triangles] = countObj(file);
    mesh.positions.reserve(vertices);
    mesh.triangles.reserve(triangles);
  }
  LineReader lines(file);
  std::string line;
  std::size_t number = 0;
  std::vector<std::uint32_t> polygon;
  std::istringstream words;
  while (lines.next(line)) {
    ++number;
    words.clear();
    words.str(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      std::array<double, 3> p;
      if (!(words >> p[0] >> p[1] >> p[2])) fail(file, fmt::format("line {}: a vertex needs x y z", number));
      checkFinite(file, p, mesh.positions.size() + 1);
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
        if (resolved < 0 || std::size_t(resolved) >= mesh.positions.size())
          fail(file,
               fmt::format("line {}: vertex index {} past the {} vertices", number, index, mesh.positions.size()));
        polygon.push_back(std::uint32_t(resolved));
      }
      addPolygon(mesh, polygon, file, number);
    }
  }
  return mesh;
}

// Binary STL repeats each corner per triangle; shared corners are merged by position.
std::uint32_t vertexOf(TriangleMesh& mesh, std::map<std::array<double, 3>, std::uint32_t>& index,
                       const std::array<double, 3>& p, const std::filesystem::path& file) {
  checkFinite(file, p, mesh.positions.size() + 1);
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
      triangle[std::size_t(corner++)] = vertexOf(mesh, index, p, file);
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
      triangle[std::size_t(c)] = vertexOf(mesh, index, {xyz[0], xyz[1], xyz[2]}, file);
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

// What a PLY header says: the format, the vertex and face elements, and where the body starts.
struct PlyHeader {
  std::string format;
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> vertex_types, vertex_names;
  std::string face_count_type, face_index_type;
  std::array<std::size_t, 3> axes{};  // the x, y and z properties among the vertex properties
  std::size_t body = 0;               // the first byte after the end_header line
};

PlyHeader readPlyHeader(const std::filesystem::path& file, const std::string& bytes) {
  const std::size_t header_end = bytes.find("end_header");
  if (bytes.rfind("ply", 0) != 0 || header_end == std::string::npos) fail(file, "not a PLY file (no ply header)");
  std::istringstream header(bytes.substr(0, header_end));
  PlyHeader h;
  std::string line, element;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "format") {
      words >> h.format;
    } else if (tag == "element") {
      std::size_t n = 0;
      words >> element >> n;
      // Every vertex and face takes at least a byte after the header: a count past the file's size is a lie
      // that must not reach an allocation.
      if (n > bytes.size())
        fail(file, fmt::format("the header says {} {} elements, more than a file of {} bytes can hold", n, element,
                               bytes.size()));
      (element == "vertex" ? h.vertices : element == "face" ? h.faces : n) = n;
    } else if (tag == "property" && element == "vertex") {
      std::string type, name;
      words >> type >> name;
      h.vertex_types.push_back(type);
      h.vertex_names.push_back(name);
    } else if (tag == "property" && element == "face") {
      std::string list;
      words >> list >> h.face_count_type >> h.face_index_type;
    }
  }
  if (h.format != "ascii" && h.format != "binary_little_endian")
    fail(file, "PLY format '" + h.format + "' is not supported (ascii or binary_little_endian)");
  for (std::size_t a = 0; a < 3; ++a) {
    const char* name = std::array{"x", "y", "z"}[a];
    const auto it = std::find(h.vertex_names.begin(), h.vertex_names.end(), name);
    if (it == h.vertex_names.end()) fail(file, fmt::format("vertices have no '{}' property", name));
    h.axes[a] = std::size_t(it - h.vertex_names.begin());
  }
  const std::size_t header_line_end = bytes.find('\n', header_end);
  if (header_line_end == std::string::npos) fail(file, "nothing follows end_header");
  h.body = header_line_end + 1;
  return h;
}

TriangleMesh readPlyAscii(const std::filesystem::path& file, const std::string& bytes, const PlyHeader& h) {
  TriangleMesh mesh;
  mesh.positions.reserve(h.vertices);
  std::istringstream in(bytes.substr(h.body));
  for (std::size_t v = 0; v < h.vertices; ++v) {
    std::vector<double> values(h.vertex_names.size());
    for (double& x : values)
      if (!(in >> x)) fail(file, fmt::format("vertex {} is incomplete", v));
    mesh.positions.push_back({values[h.axes[0]], values[h.axes[1]], values[h.axes[2]]});
    checkFinite(file, mesh.positions.back(), v);
  }
  std::vector<std::uint32_t> polygon;
  for (std::size_t f = 0; f < h.faces; ++f) {
    std::size_t n = 0;
    if (!(in >> n)) fail(file, fmt::format("face {} is incomplete", f));
    if (n > bytes.size()) fail(file, fmt::format("face {} says it has {} corners", f, n));
    polygon.assign(n, 0);
    for (auto& i : polygon)
      if (!(in >> i)) fail(file, fmt::format("face {} is incomplete", f));
    addPolygon(mesh, polygon, file, f);
  }
  return mesh;
}

// Little-endian values of the PLY scalar types, read one after another from the body.
class PlyValues {
 public:
  PlyValues(const std::filesystem::path& file, const std::string& bytes, std::size_t at)
      : file_(file), bytes_(bytes), at_(at) {}

  double next(const std::string& type) {
    const std::size_t n = sizeOf(type);
    if (at_ + n > bytes_.size()) fail(file_, "the binary data is shorter than the header says");
    const char* p = bytes_.data() + at_;
    at_ += n;
    // memcpy: the values sit at any byte offset, and a cast pointer would read them unaligned.
    if (type == "float" || type == "float32") return double(load<float>(p));
    if (type == "double" || type == "float64") return load<double>(p);
    if (n == 1) return type[0] == 'u' ? double(std::uint8_t(*p)) : double(std::int8_t(*p));
    if (n == 2) return type[0] == 'u' ? double(load<std::uint16_t>(p)) : double(load<std::int16_t>(p));
    return type[0] == 'u' ? double(load<std::uint32_t>(p)) : double(load<std::int32_t>(p));
  }

 private:
  template <typename T>
  static T load(const char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    return value;
  }
  std::size_t sizeOf(const std::string& type) const {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
      return 4;
    if (type == "double" || type == "float64") return 8;
    fail(file_, "unknown PLY type '" + type + "'");
  }
  const std::filesystem::path& file_;
  const std::string& bytes_;
  std::size_t at_;
};

TriangleMesh readPlyBinary(const std::filesystem::path& file, const std::string& bytes, const PlyHeader& h) {
  TriangleMesh mesh;
  mesh.positions.reserve(h.vertices);
  PlyValues values(file, bytes, h.body);
  for (std::size_t v = 0; v < h.vertices; ++v) {
    std::array<double, 3> p{};
    for (std::size_t k = 0; k < h.vertex_types.size(); ++k) {
      const double value = values.next(h.vertex_types[k]);
      for (std::size_t a = 0; a < 3; ++a)
        if (k == h.axes[a]) p[a] = value;
    }
    checkFinite(file, p, v);
    mesh.positions.push_back(p);
  }
  // Counts and indices must be whole numbers in range before they become sizes.
  const auto whole = [&](double value, double limit, const char* what, std::size_t f) {
    if (!(value >= 0 && value <= limit) || value != std::floor(value))
      fail(file, fmt::format("face {}: {} {} is not a whole number from 0 to {}", f, what, value, limit));
    return value;
  };
  std::vector<std::uint32_t> polygon;
  for (std::size_t f = 0; f < h.faces; ++f) {
    polygon.assign(std::size_t(whole(values.next(h.face_count_type), double(bytes.size()), "corner count", f)), 0);
    for (auto& i : polygon) i = std::uint32_t(whole(values.next(h.face_index_type), 4294967295.0, "index", f));
    addPolygon(mesh, polygon, file, f);
  }
  return mesh;
}

TriangleMesh readPly(const std::filesystem::path& file, const std::string& bytes) {
  const PlyHeader header = readPlyHeader(file, bytes);
  return header.format == "ascii" ? readPlyAscii(file, bytes, header) : readPlyBinary(file, bytes, header);
}

}  // namespace

TriangleMesh readTriangleMesh(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const std::uintmax_t size = checkReadable(file);
  TriangleMesh mesh;
  if (extension == ".obj")
    mesh = readObj(file, size);
  else if (extension == ".ply")
    mesh = readPly(file, readAll(file));
  else if (extension == ".stl")
    mesh = readStl(file, readAll(file));
  else
    fail(file, "unknown extension '" + extension + "' (use .obj, .ply or .stl)");
  if (mesh.triangles.empty()) fail(file, "it has no faces");
  return mesh;
}

}  // namespace rockbake
