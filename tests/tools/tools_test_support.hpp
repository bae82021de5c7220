#pragma once
// Shared by mpr-render's tests: a command line as mpr-render parses it, and fresh temporary
// folders.

#include "mpr-render/job.hpp"

#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace mpr_tools_test {

/// The Job of `mpr-render ARGS...` (argv[0] supplied).
inline mpr_cli::Job job_of(const std::vector<std::string>& args) {
  std::vector<const char*> argv{"mpr-render"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  return mpr_cli::parse_job(static_cast<int>(argv.size()), argv.data());
}

/// A fresh, empty temporary folder named after this process and `name`.
inline std::filesystem::path temp_folder(const std::string& name) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("mpr_tools_test_" + std::to_string(getpid()) + "_" + name);
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

} // namespace mpr_tools_test
