// The save command from the option table (save_command.hpp).
#include "save_command.hpp"

#include "option_table.hpp"

#include <cctype>
#include <string_view>

namespace mpr_cli {

std::vector<std::string> save_arguments(const Job& job, double time, int view_width, int view_height,
                                        const std::filesystem::path& output) {
  const SaveContext context{job, time, view_width, view_height, output};
  std::vector<std::string> a;
  for (const Option& o : option_table()) {
    if (o.save == nullptr || !takes(o.tools, Tools::render)) continue;
    const std::optional<std::string> value = o.save(context);
    if (!value) continue;
    a.push_back("--" + std::string(o.name));
    if (o.kind != ValueKind::flag) a.push_back(*value);
  }
  return a;
}

std::string shell_word(const std::string& s) {
  bool plain = !s.empty();
  for (const char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) ||
          std::string_view("_./,:=+-").find(c) != std::string_view::npos))
      plain = false;
  if (plain) return s;
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string save_command(const Job& job, double time, int view_width, int view_height,
                         const std::filesystem::path& output) {
  std::string line = "mpr-render";
  for (const std::string& arg : save_arguments(job, time, view_width, view_height, output))
    line.append(" ").append(shell_word(arg)); // not operator+: GCC 12's false -Wrestrict
  return line;
}

} // namespace mpr_cli
