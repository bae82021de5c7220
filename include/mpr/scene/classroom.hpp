#pragma once
/// \file
/// `mpr::scene::classroom()`: the built-in demo scene, a deterministic classroom rich in straight
/// lines and known shapes, so that multi-perspective distortions are easy to read.
///
/// World frame: metres, y up, the floor is y = 0, the room spans x in [-7, 7] and z in [-14, 12];
/// the blackboard is on the back wall z = -14 and the students face -z. Contents:
/// - a floor with 1 m checkered tiles (texture), a back wall with a 1 m grid (texture) and the left
///   wall plain; the right side and the ceiling are open (background shows);
/// - a dark green blackboard carrying the letters "GLC" built from white blocks, a red disc and a
///   yellow plus sign on the wall beside it;
/// - 3 rows of 4 desks (boxes) with a student each: a torso (cylinder) and a head (sphere), each
///   student in a distinct colour; a teacher's desk in front of the board;
/// - 8 columns (cylinders), 4 along each side.
/// Floor and walls are single quads: their boxes are flat slabs, cheap for the BVH (cutting them
/// into 1 m cells measured 6% more instructions per ray). About 17 800 triangles; nothing random, so every build is
/// identical.

#include <mpr/core/color.hpp>
#include <mpr/scene/scene.hpp>
#include <mpr/scene/shapes.hpp>
#include <mpr/scene/texture.hpp>

#include <array>
#include <cmath>
#include <concepts>

namespace mpr::scene {

namespace detail {

/// 5 x 7 block glyphs, top row first ('#' = block).
inline constexpr std::array<const char*, 7> kGlyphG = {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".###."};
inline constexpr std::array<const char*, 7> kGlyphL = {"#....", "#....", "#....", "#....", "#....", "#....", "#####"};
inline constexpr std::array<const char*, 7> kGlyphC = {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."};

/// Adds one glyph as boxes (one per horizontal run of blocks) standing out of the plane z = z0.
template <class T>
void add_glyph(scene::Scene<T>& s, const std::array<const char*, 7>& glyph, T left, T top, T cell, T z0,
               const Color& color) {
  for (int row = 0; row < 7; ++row) {
    int col = 0;
    while (col < 5) {
      if (glyph[static_cast<std::size_t>(row)][col] != '#') {
        ++col;
        continue;
      }
      int end = col;
      while (end < 5 && glyph[static_cast<std::size_t>(row)][end] == '#') ++end;
      const Vec3<T> lo(left + cell * col, top - cell * (row + 1), z0);
      const Vec3<T> hi(left + cell * end, top - cell * row, z0 + T(0.06));
      s.add(scene::box<T>(lo, hi, color), "glyph");
      col = end;
    }
  }
}

/// A saturated colour of hue `h` in [0, 1) (linear RGB).
inline Color hue(float h) {
  const float r = std::abs(h * 6 - 3) - 1, g = 2 - std::abs(h * 6 - 2), b = 2 - std::abs(h * 6 - 4);
  const Color c(std::clamp(r, 0.0f, 1.0f), std::clamp(g, 0.0f, 1.0f), std::clamp(b, 0.0f, 1.0f));
  return Color(0.04f + 0.8f * c * c); // roughly sRGB-decoded, slightly desaturated
}

} // namespace detail

/// The classroom demo scene (see the file comment).
template <std::floating_point T = float>
[[nodiscard]] scene::Scene<T> classroom() {
  using scene::box;
  using scene::cylinder;
  using scene::quad;
  using scene::sphere;
  using V = Vec3<T>;
  scene::Scene<T> s;
  s.set_background(Color(0.50f, 0.68f, 0.92f));
  scene::Lighting<T> light;
  light.towards_light = V(0.45, 1.0, 0.75);
  s.set_lighting(light);

  const int floor_tex =
      s.add_texture(scene::Texture(scene::checker_image(2, 2, Color(0.80f, 0.76f, 0.66f), Color(0.10f, 0.12f, 0.16f))));
  const int grid_tex =
      s.add_texture(scene::Texture(scene::grid_image(32, 2, Color(0.85f, 0.82f, 0.62f), Color(0.10f, 0.18f, 0.55f))));

  // Floor: 14 x 26 m (it runs on under the viewers), 1 m tiles (the
  // 2 x 2-texel checker repeats every 2 m).
  scene::Mesh<T> floor = quad<T>(V(-7, 0, 12), V(14, 0, 0), V(0, 0, -26), Color(1, 1, 1), T(7), T(13));
  floor.texture = floor_tex;
  s.add(floor, "floor");
  // Back wall with a 1 m grid, 5 m high; plain left wall.
  scene::Mesh<T> back = quad<T>(V(-7, 0, -14), V(14, 0, 0), V(0, 5, 0), Color(1, 1, 1), T(14), T(5));
  back.texture = grid_tex;
  s.add(back, "back wall");
  s.add(quad<T>(V(-7, 0, 12), V(0, 0, -26), V(0, 5, 0), Color(0.55f, 0.62f, 0.50f)), "left wall");

  // Blackboard with "GLC" in white blocks.
  s.add(box<T>(V(-3.6, 1.1, -14), V(3.6, 3.7, -13.92), Color(0.03f, 0.16f, 0.08f)), "blackboard");
  const T cell = T(0.3);
  const Color chalk(0.92f, 0.92f, 0.90f);
  detail::add_glyph<T>(s, detail::kGlyphG, T(-2.85), T(3.45), cell, T(-13.92), chalk);
  detail::add_glyph<T>(s, detail::kGlyphL, T(-0.75), T(3.45), cell, T(-13.92), chalk);
  detail::add_glyph<T>(s, detail::kGlyphC, T(1.35), T(3.45), cell, T(-13.92), chalk);
  // A red disc and a yellow plus sign on the wall.
  s.add(cylinder<T>(V(-5.3, 3.0, -14), V(0, 0, 0.08), T(0.8), Color(0.75f, 0.06f, 0.05f), 48), "disc");
  s.add(box<T>(V(4.4, 2.85, -14), V(6.2, 3.15, -13.92), Color(0.85f, 0.70f, 0.05f)), "plus");
  s.add(box<T>(V(5.15, 2.1, -14), V(5.45, 3.9, -13.92), Color(0.85f, 0.70f, 0.05f)), "plus");

  // Teacher's desk.
  s.add(box<T>(V(-1.2, 0, -12.4), V(1.2, 0.9, -11.6), Color(0.35f, 0.18f, 0.08f)), "teacher desk");

  // 3 rows x 4 desks, one student each (distinct hues).
  const Color wood(0.45f, 0.26f, 0.10f), metal(0.25f, 0.25f, 0.28f);
  const T rows[3] = {T(-9), T(-6.5), T(-4)};
  const T cols[4] = {T(-4.5), T(-1.5), T(1.5), T(4.5)};
  int student = 0;
  for (T z : rows)
    for (T x : cols) {
      s.add(box<T>(V(x - 0.7, 0.72, z - 0.4), V(x + 0.7, 0.8, z + 0.4), wood), "desk top");
      s.add(box<T>(V(x - 0.7, 0, z - 0.35), V(x - 0.62, 0.72, z + 0.35), metal), "desk leg");
      s.add(box<T>(V(x + 0.62, 0, z - 0.35), V(x + 0.7, 0.72, z + 0.35), metal), "desk leg");
      const Color c = detail::hue(static_cast<float>(student) / 12.0f);
      s.add(cylinder<T>(V(x, 0.45, z + 0.75), V(0, 0.6, 0), T(0.2), Color(0.6f * c), 24), "torso");
      s.add(sphere<T>(V(x, 1.3, z + 0.75), T(0.24), c, 32, 20), "head");
      ++student;
    }

  // Columns along both sides.
  for (T z : {T(-12.5), T(-8.5), T(-4.5), T(-0.5)}) {
    s.add(cylinder<T>(V(-6.4, 0, z), V(0, 5, 0), T(0.3), Color(0.82f, 0.80f, 0.78f), 32), "column");
    s.add(cylinder<T>(V(6.4, 0, z), V(0, 5, 0), T(0.3), Color(0.82f, 0.80f, 0.78f), 32), "column");
  }
  return s;
}

} // namespace mpr::scene
