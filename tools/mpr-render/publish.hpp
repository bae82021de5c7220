#pragma once
// All-or-nothing output of a run: every file a run writes (the image or the frames of an
// animation, the depth PFM and its preview) is first written under a hidden staging name next
// to its target, and only when every one of them is written are they renamed over their
// targets. A run that fails at any point (a render error, a full disk, a target folder that
// refuses a file) leaves every existing file as it was and writes none.

#include <mpr/core/error.hpp>
#include <mpr/io/file_write.hpp>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <span>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace mpr_cli {

/// The folder `path` is written into, checked for a run that will write there: it exists, or
/// its own parent exists (then the run creates it). A leading folder that does not exist is
/// refused rather than created (a typo in a path never builds a tree of folders). Throws
/// argument_error naming `option`.
inline void check_output_folder(const std::filesystem::path& path, const std::string& option) {
  const std::filesystem::path folder = path.parent_path();
  std::error_code ec;
  if (folder.empty() || std::filesystem::is_directory(folder, ec)) return;
  if (std::filesystem::exists(folder, ec))
    throw mpr::argument_error(option, "'" + folder.string() + "' is not a folder");
  const std::filesystem::path above = folder.parent_path();
  if (!above.empty() && !std::filesystem::is_directory(above, ec))
    throw mpr::argument_error(option, "'" + above.string() + "': no such folder (only the last folder of '" +
                                          path.string() + "' is created)");
}

/// The folder `folder` takes files now: checked as check_output_folder(folder / "x", option),
/// then made when missing and a probe file created in it exclusively, both removed again. A
/// preflight for output written after long work (--save-depth-maps after the plane sweep): a
/// folder that refuses files fails the run at once. Throws as check_output_folder, or io_error
/// naming the folder.
inline void probe_output_folder(const std::filesystem::path& folder, const std::string& option) {
  check_output_folder(folder / "x", option);
  std::error_code ec;
  bool made = false;
  if (!std::filesystem::is_directory(folder, ec)) {
    if (!std::filesystem::create_directory(folder, ec))
      throw mpr::io_error(folder.string(), "cannot create the folder: " + (ec ? ec.message() : "refused"));
    made = true;
  }
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  const std::filesystem::path probe = folder / (".mpr-probe-" + std::to_string(stamp));
  std::FILE* file = std::fopen(probe.c_str(), "wbx"); // x: never an existing file
  const int failure = file == nullptr ? errno : 0;
  if (file != nullptr) {
    std::fclose(file);
    std::filesystem::remove(probe, ec);
  }
  if (made) std::filesystem::remove(folder, ec);
  if (failure != 0)
    throw mpr::io_error(folder.string(), std::string("cannot write into the folder: ") + std::strerror(failure));
}

/// Creates the folder of `path` when check_output_folder(path, option) allows it (only the last
/// folder, never a tree); throws as check_output_folder, or io_error when the folder cannot be
/// created.
inline void create_output_folder(const std::filesystem::path& path, const std::string& option) {
  check_output_folder(path, option);
  const std::filesystem::path folder = path.parent_path();
  std::error_code ec;
  if (folder.empty() || std::filesystem::is_directory(folder, ec)) return;
  if (!std::filesystem::create_directory(folder, ec) && ec)
    throw mpr::io_error(folder.string(), "cannot create the folder: " + ec.message());
}

/// The files of one run, staged and then published together (see the file comment).
class Publication {
public:
  Publication() = default;
  Publication(const Publication&) = delete;
  Publication& operator=(const Publication&) = delete;
  /// Removes every staged file (and a folder this publication created, when empty) unless
  /// commit() ran.
  ~Publication() {
    if (committed_) return;
    std::error_code ec;
    for (const Entry& e : entries_)
      if (!e.staged.empty()) std::filesystem::remove(e.staged, ec);
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) std::filesystem::remove(*it, ec);
  }

  /// Writes `bytes` for `path` under a staging name beside it (path itself is untouched), creating
  /// path's folder when only it is missing (check_output_folder). A target that exists and is not
  /// a regular file (/dev/null, /dev/full, a FIFO) is written at commit(). Throws io_error naming
  /// `path` when the staging file cannot be written.
  void stage(const std::filesystem::path& path, std::vector<unsigned char> bytes) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
        !std::filesystem::is_directory(status)) {
      entries_.push_back({path, {}, std::move(bytes)});
      return;
    }
    if (std::filesystem::is_directory(status)) throw mpr::io_error(path.string(), "cannot write: is a folder");
    const std::filesystem::path folder = path.parent_path();
    if (!folder.empty() && !std::filesystem::exists(folder, ec)) {
      if (!std::filesystem::create_directory(folder, ec) || ec)
        throw mpr::io_error(folder.string(), "cannot create the folder: " + ec.message());
      created_.push_back(folder);
    }
    std::filesystem::path staged = path;
    // append() rather than operator+ chains: GCC 12 raises a false -Wrestrict on the latter.
    std::string name(".");
    name.append(path.filename().string()).append(".mpr-staged");
    staged.replace_filename(name);
    try {
      mpr::write_file_atomically(staged, bytes);
    } catch (const mpr::io_error& e) {
      // Name the file the user asked for, not the staging name.
      std::string why = e.what();
      const std::string staged_name = staged.string() + ": ";
      if (const auto at = why.find(staged_name); at != std::string::npos) why.erase(0, at + staged_name.size());
      throw mpr::io_error(path.string(), why);
    }
    entries_.push_back({path, staged, {}});
  }

  /// A line to print to `out` once every file is published (commit()), never before: a run that
  /// fails after staging a file does not report it as written.
  void note(std::ostream* out, std::string line) {
    if (out != nullptr) notes_.push_back({out, std::move(line)});
  }

  /// Publishes every staged file under its path: first the writes to devices (the targets that
  /// can refuse bytes, e.g. a link to /dev/full), then the renames, in the order staged, so that
  /// a device that fails leaves every regular file as it was. Then prints the notes. Throws
  /// io_error naming the file when a write to a device or a rename fails.
  void commit() {
    for (const Entry& e : entries_)
      if (e.staged.empty()) mpr::write_file_atomically(e.path, e.bytes);
    std::error_code ec;
    for (Entry& e : entries_) {
      if (e.staged.empty()) continue;
      std::filesystem::rename(e.staged, e.path, ec);
      if (ec) throw mpr::io_error(e.path.string(), "cannot replace the file: " + ec.message());
      e.staged.clear();
    }
    committed_ = true;
    for (const auto& [out, line] : notes_) *out << line << std::flush;
  }

  /// The number of files staged.
  [[nodiscard]] std::size_t size() const noexcept { return entries_.size(); }

private:
  struct Entry {
    std::filesystem::path path;
    std::filesystem::path staged;     ///< empty: written at commit() (a device or FIFO)
    std::vector<unsigned char> bytes; ///< only for those
  };
  std::vector<Entry> entries_;
  std::vector<std::filesystem::path> created_;
  std::vector<std::pair<std::ostream*, std::string>> notes_;
  bool committed_ = false;
};

} // namespace mpr_cli
