#pragma once
/// \file
/// Loading Wavefront OBJ meshes (with MTL materials and diffuse textures) into a `Scene`, through
/// tinyobjloader (Debian `libtinyobjloader-dev`). This is the only scene header that needs it:
/// link `tinyobjloader::tinyobjloader` (find_package(tinyobjloader)) when you include it.
///
/// Before tinyobjloader parses the file, every line is checked, so that a malformed file fails
/// with `io_error(path, reason, line)` naming the line: a `v` line needs 3 finite numbers
/// (optionally 3 more: a vertex colour), `vt` 2 or 3, `vn` 3; a face `f` needs at least 3
/// references `v`, `v/vt`, `v//vn` or `v/vt/vn` whose non-zero indices (negative: relative) name
/// elements defined *before* the face; a `mtllib` must exist next to the OBJ file. Other keywords
/// (o, g, s, usemtl, l, p, ...) are accepted. A file without faces is an error too.
///
/// Conversion rules: polygons are triangulated; one `Mesh` is added per material (faces without
/// a material use `ObjOptions::color`); the material's Kd is the mesh colour, unless the file
/// has vertex colours, which then win. A material's `map_Kd` image is loaded relative to the
/// OBJ file (a missing or unreadable image throws `io_error` naming the image and the material)
/// and applied to that material's faces when all of them carry texture coordinates (otherwise
/// the texture is not used). Degenerate faces are skipped by `Scene::add` (counted in
/// `Scene::degenerate_skipped()`).

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/scene/scene.hpp>
#include <mpr/scene/texture.hpp>

#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace mpr::scene {

/// Options of `add_obj`.
struct ObjOptions {
  /// Colour of faces without a material or vertex colours.
  Color color{0.8f, 0.8f, 0.8f};
  /// Uniform scale applied to every position.
  double scale = 1.0;
};

namespace detail {

/// Parses a whole-token finite number.
inline bool parse_number(const std::string& token, double& value) {
  if (token.empty()) return false;
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && std::isfinite(value);
}

/// Parses an OBJ index token (non-zero integer) and resolves it against `count` defined elements.
inline bool parse_index(const std::string& token, long long count, long long& resolved) {
  if (token.empty()) return false;
  char* end = nullptr;
  const long long i = std::strtoll(token.c_str(), &end, 10);
  if (end != token.c_str() + token.size() || i == 0) return false;
  resolved = i > 0 ? i - 1 : count + i;
  return resolved >= 0 && resolved < count;
}

/// The line-by-line check described in the file comment. Returns true when the file has vertex colours.
inline bool validate_obj(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw io_error(path.string(), "cannot open OBJ file");
  long long nv = 0, nvt = 0, nvn = 0, faces = 0;
  bool colours = false;
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream tokens(line);
    std::string key;
    if (!(tokens >> key)) continue;
    std::vector<std::string> args;
    for (std::string a; tokens >> a;) args.push_back(a);
    const auto fail = [&](const std::string& reason) { throw io_error(path.string(), reason, line_no); };
    const auto numbers = [&](std::size_t lo, std::size_t hi, const char* what) {
      if (args.size() < lo || args.size() > hi)
        fail(std::string("malformed ") + what + ": expected " + std::to_string(lo) +
             (lo == hi ? "" : " to " + std::to_string(hi)) + " numbers, found " + std::to_string(args.size()));
      double v;
      for (const std::string& a : args)
        if (!parse_number(a, v)) fail(std::string("malformed ") + what + ": '" + a + "' is not a finite number");
    };
    if (key == "v") {
      numbers(3, 7, "vertex");
      if (args.size() == 6) colours = true;
      ++nv;
    } else if (key == "vt") {
      numbers(2, 3, "texture coordinate");
      ++nvt;
    } else if (key == "vn") {
      numbers(3, 3, "normal");
      ++nvn;
    } else if (key == "f") {
      if (args.size() < 3) fail("face with fewer than 3 vertices");
      for (const std::string& ref : args) {
        std::string parts[3];
        int n = 0;
        std::size_t start = 0;
        for (;;) {
          const std::size_t slash = ref.find('/', start);
          if (n == 3) fail("malformed face reference '" + ref + "'");
          parts[n++] = ref.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
          if (slash == std::string::npos) break;
          start = slash + 1;
        }
        long long r;
        if (!parse_index(parts[0], nv, r))
          fail("face vertex index '" + parts[0] + "' is not a vertex defined so far (" + std::to_string(nv) + ")");
        if (n >= 2 && !parts[1].empty() && !parse_index(parts[1], nvt, r))
          fail("face texture index '" + parts[1] + "' is not a texture coordinate defined so far (" +
               std::to_string(nvt) + ")");
        if (n == 3 && !parse_index(parts[2], nvn, r))
          fail("face normal index '" + parts[2] + "' is not a normal defined so far (" + std::to_string(nvn) + ")");
      }
      ++faces;
    } else if (key == "mtllib") {
      if (args.empty()) fail("mtllib without a file name");
      for (const std::string& a : args) {
        const std::filesystem::path mtl = path.parent_path() / a;
        if (!std::filesystem::exists(mtl)) fail("material library '" + mtl.string() + "' not found");
      }
    }
  }
  if (faces == 0) throw io_error(path.string(), "no faces");
  return colours;
}

} // namespace detail

/// Adds the meshes of the OBJ file `path` to `scene` (see the file comment); returns the number
/// of triangles added. Throws `io_error` (with the line where it applies) or `argument_error`.
/// On error the scene may already hold some of the file's meshes.
template <std::floating_point T>
std::size_t add_obj(Scene<T>& scene, const std::filesystem::path& path, const ObjOptions& options = {}) {
  if (!std::isfinite(options.scale) || !(options.scale > 0))
    throw argument_error("scale", "must be positive and finite");
  const bool vertex_colours = detail::validate_obj(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = vertex_colours;
  config.mtl_search_path = path.parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string(), config) || !reader.Valid())
    throw io_error(path.string(), "tinyobjloader: " + reader.Error());
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::vector<tinyobj::material_t>& materials = reader.GetMaterials();

  // Group the triangles by material (-1: none).
  std::map<int, Mesh<T>> meshes;
  std::map<int, bool> all_uv;
  const T scale = static_cast<T>(options.scale);
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const std::size_t count = mesh.num_face_vertices[f];
      int material = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      if (material < 0 || material >= static_cast<int>(materials.size())) material = -1;
      Mesh<T>& m = meshes[material];
      if (!all_uv.count(material)) all_uv[material] = true;
      if (count == 3) {
        std::array<std::uint32_t, 3> tri{};
        for (std::size_t k = 0; k < 3; ++k) {
          const tinyobj::index_t index = mesh.indices[offset + k];
          const std::size_t v = static_cast<std::size_t>(index.vertex_index);
          m.positions.emplace_back(scale * static_cast<T>(attrib.vertices[3 * v]),
                                   scale * static_cast<T>(attrib.vertices[3 * v + 1]),
                                   scale * static_cast<T>(attrib.vertices[3 * v + 2]));
          if (vertex_colours && 3 * v + 2 < attrib.colors.size())
            m.colors.emplace_back(static_cast<float>(attrib.colors[3 * v]),
                                  static_cast<float>(attrib.colors[3 * v + 1]),
                                  static_cast<float>(attrib.colors[3 * v + 2]));
          if (index.texcoord_index >= 0) {
            const std::size_t t = static_cast<std::size_t>(index.texcoord_index);
            m.uvs.emplace_back(static_cast<T>(attrib.texcoords[2 * t]), static_cast<T>(attrib.texcoords[2 * t + 1]));
          } else {
            m.uvs.emplace_back(T(0), T(0));
            all_uv[material] = false;
          }
          tri[k] = static_cast<std::uint32_t>(m.positions.size() - 1);
        }
        m.triangles.push_back(tri);
      }
      offset += count;
    }
  }

  std::size_t added = 0;
  for (auto& [material, mesh] : meshes) {
    if (mesh.triangles.empty()) continue;
    if (mesh.colors.size() != mesh.positions.size()) mesh.colors.clear();
    mesh.color = options.color;
    std::string name = path.string();
    if (material >= 0) {
      const tinyobj::material_t& mat = materials[static_cast<std::size_t>(material)];
      name += " material '" + mat.name + "'";
      mesh.color = Color(static_cast<float>(mat.diffuse[0]), static_cast<float>(mat.diffuse[1]),
                         static_cast<float>(mat.diffuse[2]));
      if (!mat.diffuse_texname.empty() && all_uv[material]) {
        const std::filesystem::path image = path.parent_path() / mat.diffuse_texname;
        Image<Color> texels;
        try {
          texels = read_linear(image);
        } catch (const io_error& e) {
          throw io_error(image.string(),
                         "texture of material '" + mat.name + "' in " + path.string() + ": " + e.what());
        }
        mesh.texture = scene.add_texture(Texture(std::move(texels)));
      }
    }
    if (mesh.texture < 0) mesh.uvs.clear();
    added += scene.add(mesh, name);
  }
  return added;
}

} // namespace mpr::scene
