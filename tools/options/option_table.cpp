// The option table of mpr-render and mpr-view (option_table.hpp): its sections, declared in
// table_inputs.cpp, table_image.cpp and table_run.cpp, joined in --help order.
#include "option_table.hpp"

#include "table_sections.hpp"

#include <vector>

namespace mpr_cli {

std::span<const Option> option_table() noexcept {
  static const std::vector<Option> all = [] {
    std::vector<Option> options;
    for (const std::span<const Option> part : {table::input_options(), table::image_options(), table::run_options()})
      options.insert(options.end(), part.begin(), part.end());
    return options;
  }();
  return all;
}

const Option* find_option(std::string_view name, Tools tool) noexcept {
  for (const Option& o : option_table())
    if (o.name == name && takes(o.tools, tool)) return &o;
  return nullptr;
}

std::string_view group_title(Group group) noexcept {
  switch (group) {
  case Group::input:
    return "INPUT (the sampler; default: the classroom scene)";
  case Group::light_field:
    return "LIGHT FIELDS AND --raster";
  case Group::image:
    return "IMAGE";
  case Group::surface:
    return "IMAGE PLANE";
  case Group::animation:
    return "ANIMATION";
  case Group::run:
    return "OUTPUT AND RUN";
  case Group::viewer:
    return "VIEWER";
  }
  return "";
}

} // namespace mpr_cli
