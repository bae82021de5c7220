#pragma once
/// \file
/// Writing a whole file so that a failed write never leaves a partial file under the requested
/// name: the bytes go to a temporary file in the same folder, every write and the close are
/// checked, and only then is the temporary renamed over the target (an atomic replace on POSIX
/// file systems). On failure the temporary is removed, an existing target is left as it was,
/// and an `io_error` names the target and the reason (e.g. "No space left on device").
///
/// Targets that exist but are not regular files (`/dev/null`, `/dev/full`, a FIFO) are written
/// in place, still with every write checked; a symbolic link is followed and its target
/// replaced. A replaced file gets the permissions of a new file (the umask applies).

#include <mpr/core/error.hpp>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <span>
#include <string>
#include <system_error>

namespace mpr {

namespace detail {

/// Writes `bytes` to the open `file` and closes it; returns 0 or the errno of the first failure.
[[nodiscard]] inline int write_and_close(std::FILE* file, std::span<const unsigned char> bytes) noexcept {
  int error = 0;
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) error = errno ? errno : EIO;
  if (std::fflush(file) != 0 && error == 0) error = errno ? errno : EIO;
  if (std::ferror(file) && error == 0) error = EIO;
  if (std::fclose(file) != 0 && error == 0) error = errno ? errno : EIO;
  return error;
}

} // namespace detail

/// Replaces the file `path` with `bytes` as described in the file comment. Throws `io_error`
/// naming `path` when the folder is missing, not writable, the disk is full, or `path` is a
/// folder; the file under `path` is then unchanged (or still absent).
inline void write_file_atomically(const std::filesystem::path& path, std::span<const unsigned char> bytes) {
  std::error_code ec;
  std::filesystem::path target = path;
  if (std::filesystem::is_symlink(path, ec)) {
    target = std::filesystem::weakly_canonical(path, ec);
    if (ec) throw io_error(path.string(), "cannot follow the symbolic link: " + ec.message());
  }
  const std::filesystem::file_status status = std::filesystem::status(target, ec);
  if (std::filesystem::is_directory(status)) throw io_error(path.string(), "cannot write: is a folder");
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    // A device or FIFO: no temporary next to it (and never a rename over it).
    errno = 0;
    std::FILE* file = std::fopen(target.string().c_str(), "wb");
    if (file == nullptr) throw io_error(path.string(), std::string("cannot open for writing: ") + std::strerror(errno));
    if (const int error = detail::write_and_close(file, bytes); error != 0)
      throw io_error(path.string(), std::string("write failed: ") + std::strerror(error));
    return;
  }
  // A fresh temporary name in the same folder ("x" mode: never an existing file).
  std::random_device random;
  std::filesystem::path temporary;
  std::FILE* file = nullptr;
  int open_error = 0;
  for (int attempt = 0; attempt < 16 && file == nullptr; ++attempt) {
    const std::uint64_t tag = (std::uint64_t(random()) << 32) ^ random();
    temporary = target;
    // append() rather than operator+ chains: GCC 12 raises a false -Wrestrict on the latter.
    std::string name(".");
    name.append(target.filename().string()).append(".mpr-tmp-").append(std::to_string(tag));
    temporary.replace_filename(name);
    errno = 0;
    file = std::fopen(temporary.string().c_str(), "wbx");
    open_error = errno;
    if (file == nullptr && open_error != EEXIST) break;
  }
  if (file == nullptr)
    throw io_error(path.string(), std::string("cannot write (creating a file in its folder failed: ") +
                                      std::strerror(open_error) + ")");
  if (const int error = detail::write_and_close(file, bytes); error != 0) {
    std::filesystem::remove(temporary, ec);
    throw io_error(path.string(), std::string("write failed, nothing written: ") + std::strerror(error));
  }
  std::filesystem::rename(temporary, target, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(temporary, ec);
    throw io_error(path.string(), "cannot replace the file: " + reason);
  }
}

} // namespace mpr
