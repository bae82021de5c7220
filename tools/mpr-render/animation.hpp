#pragma once
// Animation tracks for mpr-render: a parameter that varies over the frames of an animation,
// linearly between two values ("a:b") or piecewise linearly through keyframes
// ("t0=v0,t1=v1,...", times in [0, 1] increasing, first at 0 and last at 1).

#include "cli_args.hpp"

#include <mpr/core/error.hpp>

#include <string>
#include <vector>

namespace mpr_cli {

class Track {
public:
  struct Key {
    double time;
    double value;
  };

  /// A constant track.
  explicit Track(double value = 0) : keys_{{0, value}, {1, value}} {}

  /// Parses "a:b" or "t0=v0,t1=v1,..." (see the file comment); throws argument_error naming `option`.
  static Track parse(const std::string& text, const std::string& option) {
    Track track;
    track.keys_.clear();
    if (text.find('=') == std::string::npos) {
      const std::vector<std::string> ends = split(text, ':');
      if (ends.size() != 2) throw mpr::argument_error(option, "'" + text + "' is neither FROM:TO nor T=V,T=V,...");
      track.keys_ = {{0, parse_number(ends[0], option)}, {1, parse_number(ends[1], option)}};
      return track;
    }
    for (const std::string& key : split(text, ',')) {
      const std::vector<std::string> tv = split(key, '=');
      if (tv.size() != 2) throw mpr::argument_error(option, "keyframe '" + key + "' is not TIME=VALUE");
      const double t = parse_number(tv[0], option);
      if (!track.keys_.empty() && !(t > track.keys_.back().time))
        throw mpr::argument_error(option, "keyframe times must increase");
      track.keys_.push_back({t, parse_number(tv[1], option)});
    }
    if (track.keys_.size() < 2 || track.keys_.front().time != 0 || track.keys_.back().time != 1)
      throw mpr::argument_error(option, "keyframes must start at time 0 and end at time 1");
    return track;
  }

  /// The value at `t` in [0, 1] (clamped), piecewise linear.
  [[nodiscard]] double at(double t) const noexcept {
    if (!(t > 0)) return keys_.front().value;
    if (t >= 1) return keys_.back().value;
    std::size_t i = 1;
    while (keys_[i].time < t) ++i;
    const Key& a = keys_[i - 1];
    const Key& b = keys_[i];
    const double s = (t - a.time) / (b.time - a.time);
    return a.value + s * (b.value - a.value);
  }

  [[nodiscard]] const std::vector<Key>& keys() const noexcept { return keys_; }

private:
  std::vector<Key> keys_;
};

/// An animatable value: a plain number is constant, otherwise Track::parse.
inline Track parse_track(const std::string& text, const std::string& option) {
  if (text.find(':') == std::string::npos && text.find('=') == std::string::npos)
    return Track(parse_number(text, option));
  return Track::parse(text, option);
}

/// The animation time of frame `index` of `frames`: 0 for the first, 1 for the last.
[[nodiscard]] inline double frame_time(int index, int frames) noexcept {
  return frames <= 1 ? 0.0 : static_cast<double>(index) / (frames - 1);
}

} // namespace mpr_cli
