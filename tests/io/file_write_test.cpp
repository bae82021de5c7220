#include <mpr/io/file_write.hpp>
#include <mpr/io/image_io.hpp>

#include "io/light_field_test_files.hpp"

#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> names_in(const std::filesystem::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

/// Limits the size of files this process writes (RLIMIT_FSIZE, SIGXFSZ ignored, so a write past
/// it fails with EFBIG as on a full disk) until destroyed.
class FileSizeLimit {
public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
  rlimit saved_{};
  void (*old_handler_)(int) = nullptr;
};

} // namespace

TEST_CASE("write_file_atomically replaces the whole file or nothing", "[io][file_write]") {
  const mpr_test::TempFolder dir;
  const std::string text = "first version\n";
  const std::span<const unsigned char> first(reinterpret_cast<const unsigned char*>(text.data()), text.size());
  mpr::write_file_atomically(dir / "a.txt", first);
  CHECK(read_bytes(dir / "a.txt") == text);
  CHECK(names_in(dir.path()) == std::vector<std::string>{"a.txt"});

  // A write that fails partway (the file-size limit plays a full disk) leaves the old file
  // and no temporary behind, and names the file and the reason.
  const std::vector<unsigned char> big(64 * 1024, 'x');
  {
    const FileSizeLimit limit(4096);
    try {
      mpr::write_file_atomically(dir / "a.txt", big);
      FAIL("no error for a write past the file-size limit");
    } catch (const mpr::io_error& e) {
      CHECK(e.path() == (dir / "a.txt").string());
      CHECK_THAT(e.what(), Catch::Contains("write failed") && Catch::Contains("too large"));
    }
    CHECK_THROWS_AS(mpr::write_file_atomically(dir / "new.txt", big), mpr::io_error);
  }
  CHECK(read_bytes(dir / "a.txt") == text);
  CHECK(names_in(dir.path()) == std::vector<std::string>{"a.txt"});

  // Missing folder, a folder as target.
  CHECK_THROWS_WITH(mpr::write_file_atomically(dir / "no_such_folder/x.txt", first),
                    Catch::Contains("no_such_folder/x.txt") && Catch::Contains("cannot write"));
  CHECK_THROWS_WITH(mpr::write_file_atomically(dir.path(), first), Catch::Contains("is a folder"));

  // A symbolic link: its target is replaced, the link stays.
  std::filesystem::create_symlink(dir / "a.txt", dir / "link.txt");
  mpr::write_file_atomically(dir / "link.txt", big);
  CHECK(std::filesystem::is_symlink(dir / "link.txt"));
  CHECK(std::filesystem::file_size(dir / "a.txt") == big.size());
}

TEST_CASE("write_file_atomically checks writes to devices", "[io][file_write]") {
  const std::vector<unsigned char> bytes(100, 'x');
  if (std::filesystem::exists("/dev/full")) {
    CHECK_THROWS_WITH(mpr::write_file_atomically("/dev/full", bytes),
                      Catch::Contains("/dev/full") && Catch::Contains("No space left"));
    CHECK(std::filesystem::is_character_file("/dev/full")); // written in place, never replaced
  }
  if (std::filesystem::exists("/dev/null")) CHECK_NOTHROW(mpr::write_file_atomically("/dev/null", bytes));
}

TEST_CASE("write_png never leaves a partial PNG", "[io][file_write]") {
  const mpr_test::TempFolder dir;
  mpr::Image<mpr::Rgb8> noise(300, 300);
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 300; ++x)
      noise(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(x * 7 + y * 13), static_cast<std::uint8_t>(x * y),
                              static_cast<std::uint8_t>(x ^ y)};
  {
    const FileSizeLimit limit(4096);
    CHECK_THROWS_WITH(mpr::write_png(dir / "out.png", noise), Catch::Contains("out.png") && Catch::Contains("write"));
  }
  CHECK(names_in(dir.path()).empty());
  mpr::write_png(dir / "out.png", noise);
  CHECK(mpr::read_rgb8(dir / "out.png")(299, 299) == noise(299, 299));
  CHECK_THROWS_WITH(mpr::write_png("/dev/full", noise), Catch::Contains("No space left"));
}
