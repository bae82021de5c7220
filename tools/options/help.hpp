#pragma once
// --help of mpr-render and mpr-view, generated from the option table: each option with its value,
// help, default and an example (every "e.g." runs in the test suite:
// tools/mpr-render/run_examples.cmake), grouped as the table is, then the VIEW grammar.

#include "option_table.hpp"

#include <string>
#include <string_view>

namespace mpr_cli {

/// The option lines of `tool`'s --help for the options of `group`: "  --name VALUE", the help
/// (with the default), and "e.g. EXAMPLE" when `examples`.
[[nodiscard]] std::string option_help(Group group, Tools tool, bool examples);

/// The text printed after the options by `mpr-render --help` (and mpr-view's): the VIEW
/// grammar, the ANIMATABLE values and the examples (each run by the test suite).
[[nodiscard]] std::string_view view_help() noexcept;

/// The whole of `mpr-render --help`.
[[nodiscard]] std::string render_help();

} // namespace mpr_cli
