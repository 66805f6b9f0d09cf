#include "kew/config/aerodromes.hpp"

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <system_error>

#include <fmt/format.h>

#include "kew/config/document.hpp"
#include "kew/eligibility/aerodrome_csv.hpp"

namespace kew::config {

namespace fs = std::filesystem;

std::string default_aerodromes_file() {
  // A program under the build directory is a developer's or a test's: it reads the table
  // being edited. An installed one reads its installation's, wherever that was staged
  // (cmake --install --prefix, a package's tree); the configured path when the program's
  // own cannot be known.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return KEW_INSTALLED_AERODROMES;
  const std::string build_dir = KEW_BUILD_DIR;
  if (exe.string().rfind(build_dir + "/", 0) == 0) return KEW_SOURCE_AERODROMES;
  return (exe.parent_path() / KEW_AERODROMES_FROM_BINDIR).lexically_normal().string();
}

namespace {

// Which file a table was read from, as far as the file system tells: a file replaced or
// edited in place gets another modification time or size, and is read again.
struct FileIdentity {
  std::string path;
  std::uintmax_t size = 0;
  fs::file_time_type modified;
  bool operator==(const FileIdentity&) const = default;
};

std::optional<FileIdentity> identify(const std::string& path) {
  std::error_code ec;
  FileIdentity id{path, fs::file_size(path, ec), {}};
  if (ec) return std::nullopt;
  id.modified = fs::last_write_time(path, ec);
  if (ec) return std::nullopt;
  return id;
}

// The last table read. Every configuration read (kewd's SIGHUP, a test's hundreds of
// configurations, the configuration fuzzer's every input) names the same 230 KB table;
// parsing it once per file version, not once per read, keeps a reload quick. Tables are
// immutable, so one may be shared by any number of configurations.
struct LastTable {
  std::mutex mutex;
  std::optional<FileIdentity> identity;
  std::shared_ptr<const eligibility::AerodromeTable> table;
};

LastTable& last_table() {
  static LastTable last;
  return last;
}

}  // namespace

std::shared_ptr<const eligibility::AerodromeTable> load_aerodromes(const std::string& path) {
  const std::optional<FileIdentity> before = identify(path);
  LastTable& last = last_table();
  if (before) {
    const std::lock_guard lock(last.mutex);
    if (last.identity == before) return last.table;
  }
  const std::string text = read_config_file(path, kMaxAerodromeFileBytes);
  std::shared_ptr<const eligibility::AerodromeTable> table;
  try {
    table = std::make_shared<const eligibility::AerodromeTable>(eligibility::parse_aerodrome_csv(text, path));
  } catch (const eligibility::AerodromeCsvError& e) {
    throw ConfigError(e.what());
  }
  // Remembered only when the file did not change while it was read.
  if (before && identify(path) == before) {
    const std::lock_guard lock(last.mutex);
    last.identity = before;
    last.table = table;
  }
  return table;
}

std::shared_ptr<const eligibility::AerodromeTable> load_default_aerodromes() {
  try {
    return load_aerodromes(default_aerodromes_file());
  } catch (const ConfigError& e) {
    throw ConfigError(fmt::format("{} (the default of [eligibility] aerodromes_file: name a table there)", e.what()));
  }
}

}  // namespace kew::config
