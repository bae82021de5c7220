#pragma once
/// \file
/// Loading Wavefront OBJ meshes (with MTL materials and diffuse textures) into a `Scene`, through
/// tinyobjloader (Debian `libtinyobjloader-dev`). This is the only scene header that needs it:
/// link `tinyobjloader::tinyobjloader` (find_package(tinyobjloader)) when you include it.
///
/// The file is read once, within `ObjOptions::limits` (a regular file, bounded size and line
/// length; see load_limits.hpp), and the same text is handed to tinyobjloader.
/// Before tinyobjloader parses it, every line is checked, so that a malformed file fails
/// with `io_error(path, reason, line)` naming the line: a `v` line needs 3 finite numbers
/// (optionally 3 more: a vertex colour), `vt` 2 or 3, `vn` 3; a face `f` needs at least 3
/// references `v`, `v/vt`, `v//vn` or `v/vt/vn` whose non-zero indices (negative: relative) name
/// elements defined *before* the face; a `mtllib` must exist next to the OBJ file; `vw` (skin
/// weights, a tinyobjloader extension) needs finite numbers within int's range. Other keywords
/// (o, g, s, usemtl, l, p, ...) are accepted. A file without faces is an error too. Lines end
/// at `\n`, `\r\n` or a bare `\r`; control characters other than tab are refused. After parsing,
/// every index tinyobjloader returned is checked against the arrays it read (`io_error`
/// without a line when the two readings disagree), so no input is read out of bounds.
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
#include <mpr/io/load_limits.hpp>
#include <mpr/scene/scene.hpp>
#include <mpr/scene/texture.hpp>

#include <tiny_obj_loader.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

namespace mpr::scene {

/// Options of `add_obj`.
struct ObjOptions {
  /// Colour of faces without a material or vertex colours.
  Color color{0.8f, 0.8f, 0.8f};
  /// Uniform scale applied to every position.
  double scale = 1.0;
  /// Bounds on the OBJ, MTL and texture files (load_limits.hpp).
  LoadLimits limits = {};
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
  errno = 0;
  const long long i = std::strtoll(token.c_str(), &end, 10);
  if (end != token.c_str() + token.size() || i == 0 || errno == ERANGE) return false;
  resolved = i > 0 ? i - 1 : count + i;
  return resolved >= 0 && resolved < count;
}

/// The line-by-line check of the OBJ text `text` read from `path`, described in the file
/// comment. Lines end at `\n`, `\r\n` or a bare `\r` (as in tinyobjloader); control characters
/// other than tab (NUL, form feed, vertical tab, ...) are refused, so that this check and
/// tinyobjloader see the same lines and fields. Returns true when the file has vertex colours.
inline bool validate_obj(const std::filesystem::path& path, const std::string& text) {
  long long nv = 0, nvt = 0, nvn = 0, faces = 0;
  bool colours = false;
  std::size_t line_no = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    std::size_t stop = text.find_first_of("\r\n", begin);
    if (stop == std::string::npos) stop = text.size();
    std::string line = text.substr(begin, stop - begin);
    begin = stop + (stop + 1 < text.size() && text[stop] == '\r' && text[stop + 1] == '\n' ? 2 : 1);
    ++line_no;
    const auto fail = [&](const std::string& reason) { throw io_error(path.string(), reason, line_no); };
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f) {
        char code[8];
        std::snprintf(code, sizeof code, "0x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
        fail(std::string("control character ") + code + " (OBJ text allows only tab, space and printable characters)");
      }
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream tokens(line);
    std::string key;
    if (!(tokens >> key)) continue;
    std::vector<std::string> args;
    for (std::string a; tokens >> a;) args.push_back(a);
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
    } else if (key == "vw") {
      // tinyobjloader's skin-weight extension: "vw v joint weight ...". Joint ids become int
      // inside tinyobjloader, so every number must be finite and within int's range.
      if (args.empty()) fail("malformed vertex weight: no vertex index");
      double v;
      for (const std::string& a : args)
        if (!parse_number(a, v) || std::abs(v) > 2147483647.0)
          fail("malformed vertex weight: '" + a + "' is not a finite number within int's range");
    } else if (key == "mtllib") {
      if (args.empty()) fail("mtllib without a file name");
      for (const std::string& a : args) {
        const std::filesystem::path mtl = path.parent_path() / a;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(mtl, ec)) fail("material library '" + mtl.string() + "' not found");
      }
    }
  }
  if (faces == 0) throw io_error(path.string(), "no faces");
  return colours;
}

/// tinyobjloader's material callback: reads `<folder>/<name>` within the load limits. An error
/// is kept (tinyobjloader only takes true/false) and rethrown by `add_obj` after parsing.
class BoundedMaterialReader : public tinyobj::MaterialReader {
public:
  BoundedMaterialReader(std::filesystem::path folder, const LoadLimits& limits)
      : folder_(std::move(folder)), limits_(limits) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warn, std::string* err) override {
    try {
      std::istringstream in(mpr::detail::read_text_file(folder_ / name, limits_, "MTL file"));
      tinyobj::LoadMtl(material_map, materials, &in, warn, err);
      return true;
    } catch (...) {
      if (!error_) error_ = std::current_exception();
      return false;
    }
  }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

private:
  std::filesystem::path folder_;
  LoadLimits limits_;
  std::exception_ptr error_;
};

/// Checks that every index tinyobjloader produced names an element it parsed, so that a file
/// both parsers read differently fails instead of being read out of bounds.
inline void check_parsed_indices(const std::filesystem::path& path, const tinyobj::attrib_t& attrib,
                                 const std::vector<tinyobj::shape_t>& shapes) {
  const long long nv = static_cast<long long>(attrib.vertices.size() / 3);
  const long long nvt = static_cast<long long>(attrib.texcoords.size() / 2);
  const long long nvn = static_cast<long long>(attrib.normals.size() / 3);
  for (const tinyobj::real_t x : attrib.vertices)
    if (!std::isfinite(x)) throw io_error(path.string(), "tinyobjloader read a non-finite vertex coordinate");
  for (const tinyobj::real_t x : attrib.texcoords)
    if (!std::isfinite(x)) throw io_error(path.string(), "tinyobjloader read a non-finite texture coordinate");
  for (const tinyobj::shape_t& shape : shapes) {
    std::size_t total = 0;
    for (const unsigned int count : shape.mesh.num_face_vertices) total += count;
    if (total != shape.mesh.indices.size())
      throw io_error(path.string(), "tinyobjloader returned inconsistent faces in shape '" + shape.name + "'");
    for (std::size_t k = 0; k < shape.mesh.indices.size(); ++k) {
      const tinyobj::index_t& i = shape.mesh.indices[k];
      const auto bad = [&](const char* what, int index, long long count) {
        throw io_error(path.string(), std::string("face ") + what + " index " + std::to_string(index) +
                                          " (0-based) is outside the " + std::to_string(count) + " " + what +
                                          " elements tinyobjloader read (in shape '" + shape.name + "')");
      };
      if (i.vertex_index < 0 || i.vertex_index >= nv) bad("vertex", i.vertex_index, nv);
      if (i.texcoord_index < -1 || i.texcoord_index >= nvt) bad("texture", i.texcoord_index, nvt);
      if (i.normal_index < -1 || i.normal_index >= nvn) bad("normal", i.normal_index, nvn);
    }
  }
}

} // namespace detail

/// Adds the meshes of the OBJ file `path` to `scene` (see the file comment); returns the number
/// of triangles added. Throws `io_error` (with the line where it applies) or `argument_error`.
/// On error the scene may already hold some of the file's meshes.
template <std::floating_point T>
std::size_t add_obj(Scene<T>& scene, const std::filesystem::path& path, const ObjOptions& options = {}) {
  if (!std::isfinite(options.scale) || !(options.scale > 0))
    throw argument_error("scale", "must be positive and finite");
  // Both the line check and tinyobjloader read the same bytes, read once within the limits.
  const std::string text = mpr::detail::read_text_file(path, options.limits, "OBJ file");
  const bool vertex_colours = detail::validate_obj(path, text);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  detail::BoundedMaterialReader material_reader(path.parent_path(), options.limits);
  std::istringstream in(text);
  const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &material_reader,
                                       /*triangulate=*/true, /*default_vcols_fallback=*/vertex_colours);
  material_reader.rethrow();
  if (!parsed) throw io_error(path.string(), "tinyobjloader: " + (err.empty() ? std::string("cannot parse") : err));
  detail::check_parsed_indices(path, attrib, shapes);

  // Group the triangles by material (-1: none).
  std::map<int, Mesh<T>> meshes;
  std::map<int, bool> all_uv;
  const T scale = static_cast<T>(options.scale);
  for (const tinyobj::shape_t& shape : shapes) {
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
          const Vec3<T> p(scale * static_cast<T>(attrib.vertices[3 * v]),
                          scale * static_cast<T>(attrib.vertices[3 * v + 1]),
                          scale * static_cast<T>(attrib.vertices[3 * v + 2]));
          if (!p.allFinite())
            throw io_error(path.string(), "vertex " + std::to_string(v + 1) + " times the scale " +
                                              std::to_string(options.scale) + " is not finite in " +
                                              (std::is_same_v<T, float> ? "float" : "double"));
          m.positions.push_back(p);
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
          texels = read_linear(image, options.limits);
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
