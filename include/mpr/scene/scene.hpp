#pragma once
/// \file
/// The scene model: indexed triangle meshes with per-vertex colour and optional texture
/// coordinates, textures, Lambert lighting (ambient + one directional light) and a background.
/// `Scene` flattens meshes into a triangle list that the ray caster and the rasterizer share, and
/// owns the one shading function both use, so that they produce identical colours for a hit.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/scene/texture.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace mpr::scene {

/// An indexed triangle mesh in world units. `colors` and `uvs` are per position (same length as
/// `positions`) or empty: without `colors` every vertex has `color`; `uvs` are required when
/// `texture` names a texture of the scene (index into `Scene::textures()`), ignored otherwise.
/// Triangles are counter-clockwise seen from the side their normal points to (right-handed:
/// normal = (p1 - p0) x (p2 - p0)); both sides are lit (two-sided Lambert).
template <std::floating_point T>
struct Mesh {
  std::vector<Vec3<T>> positions;
  std::vector<Color> colors;
  std::vector<Vec2<T>> uvs;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  Color color{0.8f, 0.8f, 0.8f};
  /// Texture index in the scene, or -1 for none.
  int texture = -1;
};

/// One triangle of a scene, ready for rendering. `normal` is the unit geometric normal.
template <std::floating_point T>
struct Triangle {
  std::array<Vec3<T>, 3> p;
  Vec3<T> normal;
  std::array<Color, 3> color;
  /// Texture coordinates; meaningful only when `texture >= 0`.
  std::array<Vec2<float>, 3> uv;
  /// Texture index, or -1: an untextured triangle does no texture work when shaded.
  int texture = -1;
  /// All three vertex colours are equal: shading skips their interpolation (exact flat colour).
  bool uniform_color = true;
};

/// Ambient + one directional light, Lambert: colour = albedo * (ambient + diffuse * max(0, n.l)),
/// with n the normal on the viewer's side of the triangle and l the unit direction *towards*
/// the light.
template <std::floating_point T>
struct Lighting {
  Color ambient{0.35f, 0.35f, 0.38f};
  Color diffuse{0.70f, 0.68f, 0.62f};
  /// Direction towards the light (need not be unit length; must be finite and non-zero).
  Vec3<T> towards_light = Vec3<T>(0.3, 1.0, 0.6);
};

/// A triangle scene. Building it throws on bad input; rendering it never does.
///
/// Bad input rules (checked by `add`): a mesh with no triangles, a non-finite position or uv, an
/// index out of range, colour/uv arrays of the wrong length, a missing texture index or a
/// textured mesh without uvs throw `argument_error` naming the mesh and the element.
/// *Degenerate* triangles (zero area within rounding, including repeated indices) are skipped and
/// counted in `degenerate_skipped()`: they cover no area, so dropping them changes no image.
template <std::floating_point T>
class Scene {
public:
  using scalar_type = T;

  Scene() = default;

  /// Adds a texture; returns its index for `Mesh::texture`.
  int add_texture(Texture texture) {
    textures_.push_back(std::move(texture));
    return static_cast<int>(textures_.size()) - 1;
  }

  /// Adds a mesh (see the class comment for the validation rules); `name` appears in errors.
  /// Returns the number of triangles added.
  std::size_t add(const Mesh<T>& mesh, const std::string& name = "mesh") {
    const std::size_t n = mesh.positions.size();
    if (mesh.triangles.empty()) throw argument_error(name, "has no triangles");
    if (n > std::numeric_limits<std::uint32_t>::max()) throw argument_error(name, "too many vertices");
    for (std::size_t i = 0; i < n; ++i)
      if (!mesh.positions[i].allFinite())
        throw argument_error(name, "position " + std::to_string(i) + " is not finite");
    if (!mesh.colors.empty() && mesh.colors.size() != n)
      throw argument_error(name, "colors has " + std::to_string(mesh.colors.size()) + " entries for " +
                                     std::to_string(n) + " positions");
    for (std::size_t i = 0; i < mesh.colors.size(); ++i)
      if (!mesh.colors[i].allFinite()) throw argument_error(name, "colour " + std::to_string(i) + " is not finite");
    if (!mesh.color.allFinite()) throw argument_error(name, "color is not finite");
    const bool textured = mesh.texture >= 0;
    if (textured) {
      if (mesh.texture >= static_cast<int>(textures_.size()))
        throw argument_error(name, "texture " + std::to_string(mesh.texture) + " was not added to the scene");
      if (mesh.uvs.size() != n)
        throw argument_error(name, "a textured mesh needs one uv per position (" + std::to_string(mesh.uvs.size()) +
                                       " for " + std::to_string(n) + ")");
      for (std::size_t i = 0; i < n; ++i)
        if (!mesh.uvs[i].allFinite()) throw argument_error(name, "uv " + std::to_string(i) + " is not finite");
    } else if (mesh.texture < -1) {
      throw argument_error(name, "texture index " + std::to_string(mesh.texture) + " (use -1 for none)");
    }
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
      for (std::uint32_t index : mesh.triangles[k])
        if (index >= n)
          throw argument_error(name, "triangle " + std::to_string(k) + " has index " + std::to_string(index) +
                                         " >= " + std::to_string(n) + " positions");
    std::size_t added = 0;
    triangles_.reserve(triangles_.size() + mesh.triangles.size());
    for (const auto& tri : mesh.triangles) {
      Triangle<T> t;
      for (int j = 0; j < 3; ++j) {
        t.p[j] = mesh.positions[tri[j]];
        t.color[j] = mesh.colors.empty() ? mesh.color : mesh.colors[tri[j]];
        t.uv[j] = textured ? Vec2<float>(mesh.uvs[tri[j]].template cast<float>()) : Vec2<float>::Zero();
      }
      const Vec3<T> cross = (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]);
      const T scale = std::max((t.p[1] - t.p[0]).squaredNorm(), (t.p[2] - t.p[0]).squaredNorm());
      if (!(cross.norm() > 16 * std::numeric_limits<T>::epsilon() * scale) || !cross.allFinite()) {
        ++degenerate_;
        continue;
      }
      t.normal = cross.normalized();
      t.texture = mesh.texture;
      t.uniform_color = (t.color[0] == t.color[1]).all() && (t.color[0] == t.color[2]).all();
      if (textured) ++textured_;
      triangles_.push_back(t);
      ++added;
    }
    return added;
  }

  /// Sets the light. Throws `argument_error` for a zero or non-finite direction or colours.
  void set_lighting(const Lighting<T>& lighting) {
    if (!lighting.towards_light.allFinite() || !(lighting.towards_light.norm() > 0))
      throw argument_error("towards_light", "zero or not finite");
    if (!lighting.ambient.allFinite() || !lighting.diffuse.allFinite())
      throw argument_error("lighting", "colour not finite");
    lighting_ = lighting;
    light_ = lighting.towards_light.normalized();
  }
  void set_background(const Color& background) {
    if (!background.allFinite()) throw argument_error("background", "not finite");
    background_ = background;
  }

  [[nodiscard]] const std::vector<Triangle<T>>& triangles() const noexcept { return triangles_; }
  [[nodiscard]] const std::vector<Texture>& textures() const noexcept { return textures_; }
  [[nodiscard]] const Lighting<T>& lighting() const noexcept { return lighting_; }
  [[nodiscard]] const Color& background() const noexcept { return background_; }
  [[nodiscard]] std::size_t size() const noexcept { return triangles_.size(); }
  [[nodiscard]] bool empty() const noexcept { return triangles_.empty(); }
  /// Degenerate triangles dropped by `add`.
  [[nodiscard]] std::size_t degenerate_skipped() const noexcept { return degenerate_; }
  /// Triangles that carry a texture (0: shading never touches a texture).
  [[nodiscard]] std::size_t textured_triangles() const noexcept { return textured_; }

  /// The shaded colour of triangle `index` at barycentric coordinates (b1, b2) (weights of
  /// p[1] and p[2]; p[0] gets 1 - b1 - b2), seen from the side of its normal when `front`.
  /// Precondition: index < size(). This is the only shading function of the scene: the ray
  /// caster and the rasterizer both call it.
  [[nodiscard]] Color shade(std::size_t index, T b1, T b2, bool front) const noexcept {
    const Triangle<T>& t = triangles_[index];
    const float w1 = static_cast<float>(b1), w2 = static_cast<float>(b2), w0 = 1.0f - w1 - w2;
    Color albedo = t.uniform_color ? t.color[0] : Color(w0 * t.color[0] + w1 * t.color[1] + w2 * t.color[2]);
    if (t.texture >= 0) {
      const Vec2<float> uv = w0 * t.uv[0] + w1 * t.uv[1] + w2 * t.uv[2];
      albedo *= textures_[static_cast<std::size_t>(t.texture)].sample(uv.x(), uv.y());
    }
    const T cosine = front ? t.normal.dot(light_) : -t.normal.dot(light_);
    const float lambert = cosine > 0 ? static_cast<float>(cosine) : 0.0f;
    return albedo * (lighting_.ambient + lambert * lighting_.diffuse);
  }

private:
  std::vector<Triangle<T>> triangles_;
  std::vector<Texture> textures_;
  Lighting<T> lighting_{};
  Vec3<T> light_ = Lighting<T>{}.towards_light.normalized();
  Color background_{0.55f, 0.70f, 0.90f};
  std::size_t degenerate_ = 0;
  std::size_t textured_ = 0;
};

} // namespace mpr::scene
