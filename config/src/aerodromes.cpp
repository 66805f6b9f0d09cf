#include "kew/config/aerodromes.hpp"

#include <filesystem>
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

std::shared_ptr<const eligibility::AerodromeTable> load_aerodromes(const std::string& path) {
  const std::string text = read_config_file(path, kMaxAerodromeFileBytes);
  try {
    return std::make_shared<const eligibility::AerodromeTable>(eligibility::parse_aerodrome_csv(text, path));
  } catch (const eligibility::AerodromeCsvError& e) {
    throw ConfigError(e.what());
  }
}

std::shared_ptr<const eligibility::AerodromeTable> load_default_aerodromes() {
  try {
    return load_aerodromes(default_aerodromes_file());
  } catch (const ConfigError& e) {
    throw ConfigError(fmt::format("{} (the default of [eligibility] aerodromes_file: name a table there)", e.what()));
  }
}

}  // namespace kew::config
