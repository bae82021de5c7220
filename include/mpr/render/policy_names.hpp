#pragma once
/// \file
/// The names by which a front end (mpr-render, mpr-view, the Python module) chooses mpr's
/// policies at run time: one table per choice (light-field interpolation, pixel filter, aperture
/// shape, depth-sweep neighbour selection), each name written once, and the lookups that turn a
/// name into the policy value or throw `argument_error` naming the front end's parameter with
/// the list of names ("'x' is not nearest, synthetic, cylinder or depth").

#include <mpr/core/error.hpp>
#include <mpr/glc/aperture.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/sampling/any_filter.hpp>

#include <array>
#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>
#include <system_error>

namespace mpr {

/// One name of a run-time choice: `value` is what it selects. An alias is accepted but not listed.
template <class E>
struct NamedChoice {
  std::string_view name;
  E value;
  bool alias = false;
};

/// The listed names of `table`, "a, b or c".
template <class E, std::size_t N>
[[nodiscard]] std::string choice_list(const std::array<NamedChoice<E>, N>& table) {
  std::string out;
  std::size_t listed = 0, total = 0;
  for (const NamedChoice<E>& c : table) total += c.alias ? 0 : 1;
  for (const NamedChoice<E>& c : table) {
    if (c.alias) continue;
    if (listed > 0) out += listed + 1 == total ? " or " : ", ";
    out += c.name;
    ++listed;
  }
  return out;
}

/// The value `name` selects in `table`. Throws `argument_error` naming `parameter`:
/// "'<name>' is not <choice_list>".
template <class E, std::size_t N>
[[nodiscard]] E choose(const std::array<NamedChoice<E>, N>& table, std::string_view name, std::string_view parameter) {
  for (const NamedChoice<E>& c : table)
    if (c.name == name) return c.value;
  throw argument_error(std::string(parameter), "'" + std::string(name) + "' is not " + choice_list(table));
}

/// The listed name of `value` in `table` (empty when it has none).
template <class E, std::size_t N>
[[nodiscard]] constexpr std::string_view choice_name(const std::array<NamedChoice<E>, N>& table, E value) noexcept {
  for (const NamedChoice<E>& c : table)
    if (!c.alias && c.value == value) return c.name;
  return {};
}

/// The light-field interpolations a front end offers, each a `CameraFrameSampler` policy:
/// `NearestCamera`, `SyntheticAperture`, `CylinderAperture` and `DepthProxy`.
enum class InterpolationChoice { nearest, synthetic, cylinder, depth };

inline constexpr std::array<NamedChoice<InterpolationChoice>, 5> interpolation_names{{
    {"nearest", InterpolationChoice::nearest},
    {"synthetic", InterpolationChoice::synthetic},
    {"cylinder", InterpolationChoice::cylinder},
    {"depth", InterpolationChoice::depth},
    {"synthetic_aperture", InterpolationChoice::synthetic, true},
}};

/// The reconstruction filters of supersampling (`AnyFilter`'s alternatives).
enum class FilterChoice { box, tent, gaussian, mitchell, lanczos };

inline constexpr std::array<NamedChoice<FilterChoice>, 6> filter_names{{
    {"box", FilterChoice::box},
    {"tent", FilterChoice::tent},
    {"gaussian", FilterChoice::gaussian},
    {"mitchell", FilterChoice::mitchell},
    {"lanczos", FilterChoice::lanczos},
    {"triangle", FilterChoice::tent, true},
}};

/// A filter's default radius, pixels: pbrt-v4's (box 0.5, tent 2, gaussian 1.5, mitchell 2,
/// lanczos 4).
[[nodiscard]] constexpr double default_filter_radius(FilterChoice f) noexcept {
  switch (f) {
  case FilterChoice::box:
    return 0.5;
  case FilterChoice::tent:
  case FilterChoice::mitchell:
    return 2;
  case FilterChoice::gaussian:
    return 1.5;
  case FilterChoice::lanczos:
    break;
  }
  return 4;
}

/// Filter `f` of radius `radius` pixels (0: `default_filter_radius`).
[[nodiscard]] inline AnyFilter make_filter(FilterChoice f, double radius = 0) {
  const double r = radius > 0 ? radius : default_filter_radius(f);
  switch (f) {
  case FilterChoice::box:
    return BoxFilter(r);
  case FilterChoice::tent:
    return TentFilter(r);
  case FilterChoice::gaussian:
    return GaussianFilter(r);
  case FilterChoice::mitchell:
    return MitchellFilter(r);
  case FilterChoice::lanczos:
    break;
  }
  return LanczosFilter(r);
}

/// The aperture shapes of a finite aperture (`glc::AnyAperture`'s alternatives) but the polygon,
/// which is named with its blade count ("polygon6", `aperture_by_name`).
inline constexpr std::array<NamedChoice<int>, 3> aperture_names{{{"disc", 0}, {"square", 1}, {"gaussian", 2}}};
/// The blade counts a polygon aperture may have.
inline constexpr int kMinPolygonBlades = 3, kMaxPolygonBlades = 64;

/// The aperture shape `name`: an entry of `aperture_names` or "polygonN" (N blades, 3 to 64).
/// Throws `argument_error` naming `parameter`: "'<name>' is not disc, square, gaussian or
/// polygonN (N = 3..64)", or for a polygon "'<N>' is not an integer" or "<N> is outside [3, 64]".
[[nodiscard]] inline glc::AnyAperture aperture_by_name(std::string_view name, std::string_view parameter) {
  for (const NamedChoice<int>& c : aperture_names)
    if (c.name == name) {
      if (c.value == 0) return glc::DiscAperture{};
      if (c.value == 1) return glc::SquareAperture{};
      return glc::GaussianAperture{};
    }
  constexpr std::string_view prefix = "polygon";
  if (name.size() > prefix.size() && name.substr(0, prefix.size()) == prefix) {
    const std::string_view count = name.substr(prefix.size());
    int blades = 0;
    const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), blades);
    if (ec != std::errc{} || end != count.data() + count.size())
      throw argument_error(std::string(parameter), "'" + std::string(count) + "' is not an integer");
    if (blades < kMinPolygonBlades || blades > kMaxPolygonBlades)
      throw argument_error(std::string(parameter), std::to_string(blades) + " is outside [" +
                                                       std::to_string(kMinPolygonBlades) + ", " +
                                                       std::to_string(kMaxPolygonBlades) + "]");
    return glc::PolygonAperture(blades);
  }
  std::string names;
  for (const NamedChoice<int>& c : aperture_names) (names += c.name) += ", ";
  names.resize(names.size() - 2);
  throw argument_error(std::string(parameter),
                       "'" + std::string(name) + "' is not " + names + " or polygonN (N = 3..64)");
}

/// The neighbour selections of the depth sweep (`PlaneSweepConfig::selection`).
inline constexpr std::array<NamedChoice<NeighbourSelection>, 2> neighbour_selection_names{{
    {"axes", NeighbourSelection::axes},
    {"nearest", NeighbourSelection::nearest},
}};

} // namespace mpr
