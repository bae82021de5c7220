#pragma once
/// \file
/// `mpr::AnyFilter`: one of the shipped reconstruction filters chosen at run time (e.g. from a
/// command line). The renderer visits it once per batch of samples, not per sample, so the
/// weight loop is still the filter's own inlined code.

#include <mpr/sampling/filters.hpp>
#include <mpr/sampling/pixel_sampling.hpp>

#include <variant>

namespace mpr {

/// A box, tent, Gaussian, Mitchell or Lanczos filter (default: the box of radius 0.5).
class AnyFilter {
public:
  using variant_type = std::variant<BoxFilter, TentFilter, GaussianFilter, MitchellFilter, LanczosFilter>;

  AnyFilter() = default;
  template <class F>
  requires std::constructible_from<variant_type, F> AnyFilter(F filter) : filter_(std::move(filter)) {}

  [[nodiscard]] double radius() const noexcept {
    return std::visit([](const auto& f) noexcept { return f.radius(); }, filter_);
  }
  [[nodiscard]] double evaluate(double dx, double dy) const noexcept {
    return std::visit([&](const auto& f) noexcept { return f.evaluate(dx, dy); }, filter_);
  }
  /// `fn(filter)` with the concrete filter.
  template <class Fn>
  decltype(auto) visit(Fn&& fn) const noexcept {
    return std::visit(std::forward<Fn>(fn), filter_);
  }
  [[nodiscard]] const variant_type& variant() const noexcept { return filter_; }

private:
  variant_type filter_{BoxFilter()};
};

} // namespace mpr
