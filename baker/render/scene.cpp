#include "render/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "core/hash.h"
#include "core/vec3.h"
#include "platform/atomic_file.h"
#include "preset/render_templates.h"

namespace rockbake {
namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double deg) {
  return deg * kPi / 180.0;
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

std::string povVector(const Vec3& world) {
  const Vec3 p = worldToPov(world);
  std::ostringstream s;
  s.precision(9);
  s << '<' << p[0] << ", " << p[1] << ", " << p[2] << '>';
  return s.str();
}

Vec3 boxCentre(const AssetMeshes& m) {
  return {0.5 * (double(m.bounds_min[0]) + m.bounds_max[0]), 0.5 * (double(m.bounds_min[1]) + m.bounds_max[1]),
          0.5 * (double(m.bounds_min[2]) + m.bounds_max[2])};
}

// The bounding sphere about the bounding box's centre: the farthest vertex
// (tighter than the box's half-diagonal for rounded rock); the half-diagonal
// when there are no vertices.
double radius(const AssetMeshes& m) {
  const Vec3 c = boxCentre(m);
  double r2 = 0;
  for (const SurfaceMesh* mesh : {&m.rock, &m.colluvium})
    for (const auto& p : mesh->positions) {
      const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
      r2 = std::max(r2, dx * dx + dy * dy + dz * dz);
    }
  if (r2 == 0)
    for (int i = 0; i < 3; ++i) {
      const double e = 0.5 * (double(m.bounds_max[i]) - m.bounds_min[i]);
      r2 += e * e;
    }
  return std::max(std::sqrt(r2), 1e-6);
}

// `look`: the prefix of the grain and normal the texture_list reads (<look>_Grain, <look>_Normal).
void writeMesh2(std::ostream& out, const SurfaceMesh& mesh, const std::string& name, bool mapped,
                const std::string& look) {
  const std::size_t n = mesh.positions.size();
  out << "#declare " << name << " = mesh2 {\n  vertex_vectors { " << n;
  char buf[128];
  for (const auto& p : mesh.positions) {
    // world (x, y, z) -> POV-Ray <x, z, y>
    std::snprintf(buf, sizeof buf, ",\n    <%.7g, %.7g, %.7g>", p[0], p[2], p[1]);
    out << buf;
  }
  out << "\n  }\n";
  if (mesh.normals.size() == n) {
    out << "  normal_vectors { " << n;
    for (const auto& v : mesh.normals) {
      std::snprintf(buf, sizeof buf, ",\n    <%.6g, %.6g, %.6g>", v[0], v[2], v[1]);
      out << buf;
    }
    out << "\n  }\n";
  }
  if (mapped) {
    // POV-Ray's image v runs up the image, glTF's down it.
    out << "  uv_vectors { " << n;
    for (const auto& uv : mesh.uvs) {
      std::snprintf(buf, sizeof buf, ",\n    <%.7g, %.7g>", uv[0], 1.0f - uv[1]);
      out << buf;
    }
    out << "\n  }\n#if (Rockbake_Use_Maps)\n  face_indices { " << mesh.triangles.size();
    for (const auto& t : mesh.triangles) {
      std::snprintf(buf, sizeof buf, ",\n    <%u, %u, %u>", t[0], t[1], t[2]);
      out << buf;
    }
    out << "\n  }\n  texture { Rockbake_Mapped }\n#else\n";
  }
  // One texture per distinct colour, not per vertex: POV-Ray builds a texture
  // object for every entry, and parsing them dominated the render of a large
  // asset. Colours are rounded to 1/4096 (linear), far below what 8-bit
  // previews or half-float renders resolve; indices follow first use, so the
  // file is a function of the mesh alone.
  std::vector<std::uint32_t> texture_of(n);
  std::vector<std::array<std::uint32_t, 3>> textures;
  std::unordered_map<std::uint64_t, std::uint32_t> index_of;
  index_of.reserve(n / 8 + 1);
  const auto level = [](float v) { return std::uint64_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 4095.0f)); };
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<float, 3> c = i < mesh.colors.size() ? mesh.colors[i] : std::array<float, 3>{0.18f, 0.18f, 0.18f};
    const std::uint64_t key = level(c[0]) << 24 | level(c[1]) << 12 | level(c[2]);
    const auto [it, fresh] = index_of.try_emplace(key, std::uint32_t(textures.size()));
    if (fresh)
      textures.push_back({std::uint32_t(key >> 24), std::uint32_t(key >> 12 & 4095), std::uint32_t(key & 4095)});
    texture_of[i] = it->second;
  }
  out << "  texture_list { " << textures.size();
  for (const auto& c : textures) {
    // The vertex colour, varied by the template's grain pattern between
    // Rockbake_Dark and Rockbake_Light times itself, with its bump and finish.
    char rgb[96];
    std::snprintf(rgb, sizeof rgb, "rgb <%.6g, %.6g, %.6g>", c[0] / 4095.0, c[1] / 4095.0, c[2] / 4095.0);
    out << ",\n    texture { pigment { pigment_pattern { " << look << "_Grain } color_map { [0 " << rgb
        << " * Rockbake_Dark] [1 " << rgb << " * Rockbake_Light] } } normal { " << look
        << "_Normal } finish { Rockbake_Finish } }";
  }
  out << "\n  }\n  face_indices { " << mesh.triangles.size();
  for (const auto& t : mesh.triangles) {
    std::snprintf(buf, sizeof buf, ",\n    <%u, %u, %u>, %u, %u, %u", t[0], t[1], t[2], texture_of[t[0]],
                  texture_of[t[1]], texture_of[t[2]]);
    out << buf;
  }
  out << (mapped ? "\n  }\n#end\n}\n" : "\n  }\n}\n");
}

// The stones (core/clast_set.h), placed and merged into one mesh2, Rockbake_Clasts, in vertex
// colours with the rock's grain and bump, and the apron redeclared as the union of its surface and
// the stones, so that every template that shows Rockbake_Colluvium shows them. One mesh of every
// stone's triangles traces faster than an object per stone (its octree bounds them all).
void writeClasts(std::ostream& out, const ClastSet& set) {
  SurfaceMesh all;
  all.name = "clasts";
  for (const ClastInstance& stone : set.stones) {
    const SurfaceMesh& shape = set.shapes.at(std::size_t(stone.shape));
    const auto base = std::uint32_t(all.positions.size());
    ClastInstance turn = stone;  // the rotation alone, for the normals
    turn.translation = {0, 0, 0};
    turn.scale = 1.0;
    for (std::size_t v = 0; v < shape.positions.size(); ++v) {
      const auto p = clastVertex(stone, shape.positions[v]);
      all.positions.push_back({float(p[0]), float(p[1]), float(p[2])});
      if (shape.normals.size() == shape.positions.size()) {
        const auto n = clastVertex(turn, shape.normals[v]);
        all.normals.push_back({float(n[0]), float(n[1]), float(n[2])});
      }
      all.colors.push_back(v < shape.colors.size() ? shape.colors[v] : std::array<float, 3>{0.18f, 0.18f, 0.18f});
    }
    for (const auto& t : shape.triangles) all.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  if (all.normals.size() != all.positions.size()) all.normals.clear();
  writeMesh2(out, all, "Rockbake_Clasts", false, "Rockbake_Rock");
  out << "#declare Rockbake_Colluvium = union {\n  object { Rockbake_Colluvium_Apron }\n  object { Rockbake_Clasts "
         "}\n}\n";
}

// The texture a template gets with Rockbake_Use_Maps: the base colour through the uvs (no bump: RenderMaps).
void writeMappedTexture(std::ostream& out, const RenderMaps& maps) {
  out << "#declare Rockbake_Has_Maps = 1;\n#ifndef (Rockbake_Use_Maps)\n#declare Rockbake_Use_Maps = 0;\n#end\n"
      << "#declare Rockbake_Mapped = texture {\n  uv_mapping\n  pigment { image_map { png \"" << maps.base_color
      << "\" gamma srgb interpolate 2 } }\n";
  out << "  finish { Rockbake_Finish }\n}\n";
}

}  // namespace

Vec3 worldToPov(const Vec3& w) {
  return {w[0], w[2], w[1]};
}

Vec3 AssetFrame::centre() const {
  return {0.5 * (bounds_min[0] + bounds_max[0]), 0.5 * (bounds_min[1] + bounds_max[1]),
          0.5 * (bounds_min[2] + bounds_max[2])};
}

AssetFrame assetFrame(const AssetMeshes& m) {
  AssetFrame f;
  for (int i = 0; i < 3; ++i) f.bounds_min[i] = m.bounds_min[i], f.bounds_max[i] = m.bounds_max[i];
  f.radius = radius(m);
  return f;
}

AssetFrame readAssetFrame(const std::filesystem::path& include) {
  std::ifstream in(include);
  std::string line;
  const std::string tag = "// rockbake-frame:";
  for (int i = 0; i < 16 && std::getline(in, line); ++i) {
    if (line.rfind(tag, 0) != 0) continue;
    std::istringstream s(line.substr(tag.size()));
    AssetFrame f;
    s >> f.bounds_min[0] >> f.bounds_min[1] >> f.bounds_min[2] >> f.bounds_max[0] >> f.bounds_max[1] >>
        f.bounds_max[2] >> f.radius;
    if (s && f.radius > 0) return f;
    break;
  }
  throw std::runtime_error(
      "cannot re-render from " + include.string() +
      ": missing or not a rockbake mesh include (no '// rockbake-frame:' line); bake the asset again");
}

CameraSetup frameCamera(const AssetMeshes& meshes, int width, int height, double turntable_deg, double angle_deg) {
  return frameCamera(assetFrame(meshes), width, height, turntable_deg, angle_deg);
}

CameraSetup frameCamera(const AssetFrame& meshes, int width, int height, double turntable_deg, double angle_deg) {
  constexpr double kFill = 0.92;  // the asset's extent may use 92 % of the narrower direction
  const double tan_h = std::tan(radians(angle_deg) / 2.0) * kFill;
  const double tan_v = std::tan(radians(angle_deg) / 2.0) * double(height) / double(std::max(width, 1)) * kFill;
  const double az = radians(-60.0 + turntable_deg);
  const double el = radians(20.0);
  const Vec3 c = meshes.centre();
  // Unit vectors, world frame: `back` from the centre towards the camera.
  const Vec3 back{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  const Vec3 right{-std::sin(az), std::cos(az), 0.0};  // back × z, normalised: screen right
  // back × right: screen up.
  const Vec3 up = cross(back, right);

  // Two sufficient distances; the nearer wins. (1) The bounding sphere just
  // fits the narrower field of view. (2) Every corner of the bounding box
  // projects inside the frame.
  const double r = meshes.radius;
  const double d_sphere = r / std::sin(std::atan(std::min(tan_h, tan_v)));
  double d_box = 0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 p{(i & 1 ? meshes.bounds_max[0] : meshes.bounds_min[0]) - c[0],
                 (i & 2 ? meshes.bounds_max[1] : meshes.bounds_min[1]) - c[1],
                 (i & 4 ? meshes.bounds_max[2] : meshes.bounds_min[2]) - c[2]};
    const double toward = dot(p, back);  // the corner's depth is d - toward
    d_box = std::max(
        {d_box, std::abs(dot(p, right)) / tan_h + toward, std::abs(dot(p, up)) / tan_v + toward, toward + 1e-3 * r});
  }
  const double d = std::max(std::min(d_sphere, d_box), 1.05 * r);
  CameraSetup cam;
  cam.look_at = c;
  cam.location = {c[0] + d * back[0], c[1] + d * back[1], c[2] + d * back[2]};
  cam.angle_deg = angle_deg;
  return cam;
}

void writeMeshInclude(const AssetMeshes& meshes, const std::filesystem::path& file, const RenderMaps& maps,
                      const ClastSet* clasts) {
  if (meshes.rock.positions.empty() || meshes.rock.triangles.empty())
    throw std::runtime_error("cannot write " + file.string() + ": the rock mesh has no triangles");
  const bool mapped = !maps.empty();
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium})
    if (mapped && m->uvs.size() != m->positions.size())
      throw std::runtime_error("cannot write " + file.string() + ": the " + m->name + " mesh has maps but no uvs");
  const bool colluvium = !meshes.colluvium.positions.empty() && !meshes.colluvium.triangles.empty();
  writeFileAtomically(file, [&](std::ostream& out) {
    const AssetFrame f = assetFrame(meshes);
    char frame[256];
    std::snprintf(frame, sizeof frame, "// rockbake-frame: %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", f.bounds_min[0],
                  f.bounds_min[1], f.bounds_min[2], f.bounds_max[0], f.bounds_max[1], f.bounds_max[2], f.radius);
    out << "// Written by rockbake: the asset's meshes in POV-Ray's frame (world x, y, z -> <x, z, y>).\n"
        << "// World bounding box (min, max, z up) and bounding-sphere radius, for re-rendering:\n"
        << frame << "#ifndef (Rockbake_Finish)\n#declare Rockbake_Finish = finish { diffuse 0.8 }\n#end\n";
    // The material a template may declare before the include; by default the
    // vertex colour exactly, unbumped.
    for (const char* surface : {"Rockbake_Rock", "Rockbake_Colluvium"})
      out << "#ifndef (" << surface << "_Grain)\n#declare " << surface << "_Grain = pigment { rgb 0.5 }\n#end\n"
          << "#ifndef (" << surface << "_Normal)\n#declare " << surface << "_Normal = normal { granite 0 }\n#end\n";
    out << "#ifndef (Rockbake_Dark)\n#declare Rockbake_Dark = 1;\n#end\n"
        << "#ifndef (Rockbake_Light)\n#declare Rockbake_Light = 1;\n#end\n";
    if (mapped) writeMappedTexture(out, maps);
    writeMesh2(out, meshes.rock, "Rockbake_Rock", mapped, "Rockbake_Rock");
    const bool stones = colluvium && clasts && !clasts->stones.empty();
    if (colluvium)
      writeMesh2(out, meshes.colluvium, stones ? "Rockbake_Colluvium_Apron" : "Rockbake_Colluvium", mapped,
                 "Rockbake_Colluvium");
    if (stones) writeClasts(out, *clasts);
    out << "#declare Rockbake_Has_Colluvium = " << (colluvium ? 1 : 0) << ";\n";
  });
}

std::map<std::string, std::string> scenePlaceholders(const AssetFrame& meshes, const CameraSetup& camera,
                                                     const CameraSetup& home, const SceneFrame& frame,
                                                     const std::string& mesh_include, std::uint64_t seed) {
  // Where the template's patterns are sampled: seeded, so each rock's grain differs.
  Vec3 offset;
  for (int a = 0; a < 3; ++a)
    offset[a] = std::round(1e4 * 1000.0 * unitInterval(counterHash(seed, purposeId("render-pattern"), 0, a))) / 1e4;
  return {
      {"SEED_OFFSET", "<" + num(offset[0]) + ", " + num(offset[1]) + ", " + num(offset[2]) + ">"},
      {"MESH_INCLUDE", mesh_include},
      {"CAMERA_LOCATION", povVector(camera.location)},
      {"CAMERA_LOOK_AT", povVector(camera.look_at)},
      {"CAMERA_ANGLE", num(camera.angle_deg)},
      {"CAMERA_HOME", povVector(home.location)},
      {"ASSET_CENTER", povVector(meshes.centre())},
      {"ASSET_RADIUS", num(meshes.radius)},
      {"BOUNDS_MIN", povVector({meshes.bounds_min[0], meshes.bounds_min[1], meshes.bounds_min[2]})},
      {"BOUNDS_MAX", povVector({meshes.bounds_max[0], meshes.bounds_max[1], meshes.bounds_max[2]})},
      {"GROUND_Z", num(meshes.bounds_min[2])},
      {"FRAME", std::to_string(frame.frame)},
      {"FRAMES", std::to_string(frame.frames)},
      {"TURNTABLE_ANGLE", num(frame.turntable_deg)},
      {"LOOKDEV", frame.lookdev ? "1" : "0"},
  };
}

std::filesystem::path findTemplate(const std::filesystem::path& dir, const std::string& name) {
  // A name, never a path: nothing outside the templates folder is read.
  if (renderTemplateProblem(name, dir))
    throw std::runtime_error("render template '" + name + "': " + *renderTemplateProblem(name, dir));
  const auto file = dir / (name + ".pov");
  if (std::filesystem::is_regular_file(file)) return file;
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".pov") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw std::runtime_error("render template '" + name + "' not found: no " + file.string() +
                           (list.empty() ? std::string(" (the folder has no templates)") : "; available: " + list));
}

std::string fillTemplate(std::string_view text, const std::map<std::string, std::string>& values,
                         const std::string& label) {
  std::string out;
  out.reserve(text.size() + 256);
  std::size_t pos = 0;
  while (true) {
    const std::size_t open = text.find("{{", pos);
    if (open == std::string_view::npos) break;
    const std::size_t close = text.find("}}", open + 2);
    const int line = 1 + int(std::count(text.begin(), text.begin() + open, '\n'));
    if (close == std::string_view::npos)
      throw std::runtime_error(label + ":" + std::to_string(line) + ": unterminated placeholder '{{'");
    const std::string name(text.substr(open + 2, close - open - 2));
    const auto it = values.find(name);
    if (it == values.end()) {
      std::string known;
      for (const auto& [k, v] : values) known += (known.empty() ? "" : ", ") + k;
      throw std::runtime_error(label + ":" + std::to_string(line) + ": unknown placeholder {{" + name +
                               "}}; known placeholders: " + known);
    }
    out.append(text.substr(pos, open - pos));
    out += it->second;
    pos = close + 2;
  }
  out.append(text.substr(pos));
  return out;
}

void writeScene(const std::filesystem::path& template_file, const std::map<std::string, std::string>& values,
                const std::filesystem::path& scene_file) {
  std::ifstream in(template_file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read render template " + template_file.string());
  std::ostringstream text;
  text << in.rdbuf();
  writeFileAtomically(scene_file, fillTemplate(text.str(), values, template_file.string()));
}

}  // namespace rockbake
