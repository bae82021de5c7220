#pragma once
// The command line of mpr-render or mpr-view -> OptionValues, through CLI11 (Debian's
// libcli11-dev) set up from the option table. On top of CLI11, whose errors do not name the fix,
// the arguments are checked first so that every mistake is one line naming the option: an
// unknown option with the nearest known one ("did you mean --view?"), an option whose value is
// missing ("needs a value VIEW before --output"), a flag given a value, a stray word.

#include "option_table.hpp"
#include "option_values.hpp"

#include <cstddef>
#include <string>
#include <string_view>

namespace mpr_cli {

/// The edit distance (insertions, deletions, substitutions, transpositions of neighbours) between
/// `a` and `b`.
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

/// "; did you mean --NAME?" for the option `tool` takes nearest to the unknown `name` (at most 2
/// edits, and fewer than half its letters), else "".
[[nodiscard]] std::string did_you_mean(std::string_view name, Tools tool);

/// Parses argv (argv[0] skipped) against the options `tool` takes. Throws mpr::argument_error for
/// unknown options, missing values, flags given a value and stray arguments; the values
/// themselves are checked when read (OptionValues).
[[nodiscard]] OptionValues parse_options(int argc, const char* const* argv, Tools tool);

} // namespace mpr_cli
