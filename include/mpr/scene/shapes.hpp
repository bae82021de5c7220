#pragma once
/// \file
/// Mesh builders for the shapes a synthetic scene is made of: quads, axis-aligned boxes, UV
/// spheres and capped cylinders. All produce outward-facing, counter-clockwise triangles in world
/// units and throw `argument_error` naming the parameter for non-finite or degenerate input.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/scene/scene.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>

namespace mpr::scene {

namespace detail {
template <class T>
void require_finite(const Vec3<T>& v, const char* name) {
  if (!v.allFinite()) throw argument_error(name, "not finite");
}
template <class T>
std::uint32_t push(Mesh<T>& m, const Vec3<T>& p, const Vec2<T>& uv = Vec2<T>::Zero()) {
  m.positions.push_back(p);
  m.uvs.push_back(uv);
  return static_cast<std::uint32_t>(m.positions.size() - 1);
}
/// Appends the quad origin, origin + u, origin + u + v, origin + v (normal u x v).
template <class T>
void append_quad(Mesh<T>& m, const Vec3<T>& origin, const Vec3<T>& u, const Vec3<T>& v, T uv_u, T uv_v) {
  const std::uint32_t a = push(m, origin, Vec2<T>(0, 0));
  const std::uint32_t b = push(m, Vec3<T>(origin + u), Vec2<T>(uv_u, 0));
  const std::uint32_t c = push(m, Vec3<T>(origin + u + v), Vec2<T>(uv_u, uv_v));
  const std::uint32_t d = push(m, Vec3<T>(origin + v), Vec2<T>(0, uv_v));
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}
} // namespace detail

/// The parallelogram `origin + a u + b v`, a, b in [0, 1], normal `u x v`, cut into
/// `divisions_u` x `divisions_v` cells of two triangles each (cells keep bounding boxes small, which
/// a BVH needs: one huge floor triangle would overlap every box above it). Texture coordinates run
/// from (0, 0) at `origin` to (`repeat_u`, `repeat_v`) at the opposite corner, so a texture
/// repeats `repeat_u` times along `u`. Vertices are shared between cells (a watertight grid).
template <std::floating_point T>
[[nodiscard]] Mesh<T> quad(const Vec3<T>& origin, const Vec3<T>& u, const Vec3<T>& v, const Color& color,
                           T repeat_u = 1, T repeat_v = 1, int divisions_u = 1, int divisions_v = 1) {
  detail::require_finite(origin, "origin");
  detail::require_finite(u, "u");
  detail::require_finite(v, "v");
  if (!(u.cross(v).norm() > 0)) throw argument_error("v", "zero or parallel to u: the quad is degenerate");
  if (!std::isfinite(repeat_u) || !std::isfinite(repeat_v)) throw argument_error("repeat", "not finite");
  if (divisions_u < 1 || divisions_v < 1 || divisions_u > 4096 || divisions_v > 4096)
    throw argument_error("divisions", "must be between 1 and 4096");
  Mesh<T> m;
  m.color = color;
  for (int j = 0; j <= divisions_v; ++j)
    for (int i = 0; i <= divisions_u; ++i) {
      const T a = static_cast<T>(i) / static_cast<T>(divisions_u), b = static_cast<T>(j) / static_cast<T>(divisions_v);
      detail::push(m, Vec3<T>(origin + a * u + b * v), Vec2<T>(a * repeat_u, b * repeat_v));
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (divisions_u + 1) + i); };
  for (int j = 0; j < divisions_v; ++j)
    for (int i = 0; i < divisions_u; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

/// The axis-aligned box [lo, hi], 12 triangles, each face with uv (0,0)-(1,1).
/// Throws `argument_error("hi", ...)` unless hi > lo in every coordinate.
template <std::floating_point T>
[[nodiscard]] Mesh<T> box(const Vec3<T>& lo, const Vec3<T>& hi, const Color& color) {
  detail::require_finite(lo, "lo");
  detail::require_finite(hi, "hi");
  if (!(hi.x() > lo.x() && hi.y() > lo.y() && hi.z() > lo.z()))
    throw argument_error("hi", "must exceed lo in x, y and z");
  const Vec3<T> d = hi - lo;
  const Vec3<T> X(d.x(), 0, 0), Y(0, d.y(), 0), Z(0, 0, d.z());
  Mesh<T> m;
  m.color = color;
  detail::append_quad(m, Vec3<T>(hi.x(), lo.y(), lo.z()), Y, Z, T(1), T(1)); // +x
  detail::append_quad(m, lo, Z, Y, T(1), T(1));                              // -x
  detail::append_quad(m, Vec3<T>(lo.x(), hi.y(), lo.z()), Z, X, T(1), T(1)); // +y
  detail::append_quad(m, lo, X, Z, T(1), T(1));                              // -y
  detail::append_quad(m, Vec3<T>(lo.x(), lo.y(), hi.z()), X, Y, T(1), T(1)); // +z
  detail::append_quad(m, lo, Y, X, T(1), T(1));                              // -z
  return m;
}

/// A UV sphere: `stacks` rings from the +y pole to the -y pole, `slices` segments around y.
/// Pole caps are fans (no degenerate triangles). Requires radius > 0, slices >= 3, stacks >= 2.
template <std::floating_point T>
[[nodiscard]] Mesh<T> sphere(const Vec3<T>& centre, T radius, const Color& color, int slices = 24, int stacks = 16) {
  detail::require_finite(centre, "centre");
  if (!(radius > 0) || !std::isfinite(radius)) throw argument_error("radius", "must be positive and finite");
  if (slices < 3) throw argument_error("slices", "must be at least 3");
  if (stacks < 2) throw argument_error("stacks", "must be at least 2");
  Mesh<T> m;
  m.color = color;
  const auto index = [&](int i, int j) { return static_cast<std::uint32_t>(i * (slices + 1) + j); };
  for (int i = 0; i <= stacks; ++i) {
    const T theta = std::numbers::pi_v<T> * static_cast<T>(i) / static_cast<T>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const T phi = 2 * std::numbers::pi_v<T> * static_cast<T>(j % slices) / static_cast<T>(slices);
      const Vec3<T> dir(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      const Vec3<T> p = (i == 0 || i == stacks) ? Vec3<T>(centre + radius * Vec3<T>(0, i == 0 ? 1 : -1, 0))
                                                : Vec3<T>(centre + radius * dir);
      detail::push(m, p, Vec2<T>(static_cast<T>(j) / slices, 1 - static_cast<T>(i) / stacks));
    }
  }
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const std::uint32_t a = index(i, j), b = index(i, j + 1), c = index(i + 1, j + 1), d = index(i + 1, j);
      if (i != 0) m.triangles.push_back({a, b, c});
      if (i != stacks - 1) m.triangles.push_back({a, c, d});
    }
  return m;
}

/// A capped cylinder from `base` to `base + axis` with `segments` sides.
/// Requires a non-zero axis, radius > 0, segments >= 3.
template <std::floating_point T>
[[nodiscard]] Mesh<T> cylinder(const Vec3<T>& base, const Vec3<T>& axis, T radius, const Color& color,
                               int segments = 32) {
  detail::require_finite(base, "base");
  detail::require_finite(axis, "axis");
  if (!(axis.norm() > 0)) throw argument_error("axis", "zero length");
  if (!(radius > 0) || !std::isfinite(radius)) throw argument_error("radius", "must be positive and finite");
  if (segments < 3) throw argument_error("segments", "must be at least 3");
  const Vec3<T> a = axis.normalized();
  const Vec3<T> helper = std::abs(a.x()) < T(0.9) ? Vec3<T>::UnitX() : Vec3<T>::UnitY();
  const Vec3<T> e1 = helper.cross(a).normalized();
  const Vec3<T> e2 = a.cross(e1);
  Mesh<T> m;
  m.color = color;
  const std::uint32_t bottom_centre = detail::push(m, base);
  const std::uint32_t top_centre = detail::push(m, Vec3<T>(base + axis));
  for (int j = 0; j < segments; ++j) {
    const T phi = 2 * std::numbers::pi_v<T> * static_cast<T>(j) / static_cast<T>(segments);
    const Vec3<T> b = base + radius * (std::cos(phi) * e1 + std::sin(phi) * e2);
    detail::push(m, b);
    detail::push(m, Vec3<T>(b + axis));
  }
  const auto bottom = [&](int j) { return static_cast<std::uint32_t>(2 + 2 * (j % segments)); };
  const auto top = [&](int j) { return static_cast<std::uint32_t>(3 + 2 * (j % segments)); };
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({bottom(j), bottom(j + 1), top(j + 1)});
    m.triangles.push_back({bottom(j), top(j + 1), top(j)});
    m.triangles.push_back({top_centre, top(j), top(j + 1)});
    m.triangles.push_back({bottom_centre, bottom(j + 1), bottom(j)});
  }
  return m;
}

} // namespace mpr::scene
