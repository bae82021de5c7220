// The command line through CLI11, set up from the option table (parse.hpp).
#include "parse.hpp"

#include <mpr/core/error.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <utility>
#include <vector>

namespace mpr_cli {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string did_you_mean(std::string_view name, Tools tool) {
  const Option* best = nullptr;
  std::size_t best_distance = 3;
  for (const Option& o : option_table())
    if (takes(o.tools, tool))
      if (const std::size_t d = edit_distance(name, o.name); d < best_distance && 2 * d < name.size())
        best = &o, best_distance = d;
  return best == nullptr ? std::string() : "; did you mean --" + std::string(best->name) + "?";
}

namespace {

/// The checks CLI11 does not word for the user: each argument is a known option, a flag has no
/// value, and an option's value is there (not the next option).
std::vector<std::string> check_arguments(int argc, const char* const* argv, Tools tool) {
  std::vector<std::string> args; // argv[1..] for CLI11, "--name=" as "--name" ""
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0)
      throw mpr::argument_error(arg, "unexpected argument (options start with --; see --help)");
    std::string name = arg.substr(2);
    const std::size_t eq = name.find('=');
    const bool inline_value = eq != std::string::npos;
    if (inline_value) name.resize(eq);
    const Option* option = find_option(name, tool);
    if (option == nullptr)
      throw mpr::argument_error("--" + name, "unknown option" + did_you_mean(name, tool) + " (see --help)");
    const std::string value(option->value);
    args.push_back(arg);
    if (option->kind == ValueKind::flag) {
      if (inline_value) throw mpr::argument_error("--" + name, "is a flag and takes no value");
    } else if (inline_value && eq + 3 == arg.size()) {
      args.back().pop_back(); // an empty value, read as the option's (CLI11 refuses "--name=")
      args.emplace_back();
    } else if (!inline_value) {
      if (i + 1 >= argc) throw mpr::argument_error("--" + name, "needs a value " + value);
      // "--view --output a.png": the value of --view is missing, not a.png misplaced.
      if (const std::string next = argv[i + 1]; next.rfind("--", 0) == 0 && next.size() > 2)
        throw mpr::argument_error("--" + name, "needs a value " + value + " before " + next);
      args.emplace_back(argv[++i]);
    }
  }
  return args;
}

} // namespace

OptionValues parse_options(int argc, const char* const* argv, Tools tool) {
  std::vector<std::string> args = check_arguments(argc, argv, tool);
  CLI::App app;
  app.set_help_flag(); // --help is an entry of the table, answered before parsing
  std::vector<std::pair<const Option*, CLI::Option*>> declared;
  for (const Option& o : option_table()) {
    if (!takes(o.tools, tool)) continue;
    const std::string flag = "--" + std::string(o.name);
    CLI::Option* cli = o.kind == ValueKind::flag ? app.add_flag(flag)
                                                 : app.add_option(flag)
                                                       ->type_name(std::string(o.value))
                                                       ->expected(1)
                                                       ->allow_extra_args(false)
                                                       ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cli->description(std::string(o.help));
    declared.emplace_back(&o, cli);
  }
  std::reverse(args.begin(), args.end()); // CLI11 takes them reversed
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    // Only what check_arguments lets through reaches here (a value CLI11 reads as an option).
    throw mpr::argument_error("command line", e.what());
  }
  OptionValues values;
  for (const auto& [option, cli] : declared) {
    if (cli->count() == 0) continue;
    if (option->kind == ValueKind::flag) {
      values.add(option->name, "");
    } else {
      for (const std::string& v : cli->results()) values.add(option->name, v);
    }
  }
  return values;
}

} // namespace mpr_cli
