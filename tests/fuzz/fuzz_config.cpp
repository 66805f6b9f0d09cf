// libFuzzer target: any bytes as a kewd configuration file (daemon/include/kew/daemon/
// config.hpp, the TOML reader of config/). Every input is either read into a Config or
// refused with a ConfigError that says where and why; any other exception, crash or
// sanitizer report is a finding. Paths are not checked (that is --check-config's work);
// a [regions] geojson file and an [eligibility] aerodromes_file are opened, relative to the
// run's working directory, and without one kew's aerodrome table (the source tree's
// data/aerodromes.csv: the fuzzer runs from the build tree) is used, parsed once for
// the whole run (config/src/aerodromes.cpp keeps the last table read).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "kew/config/config_error.hpp"
#include "kew/daemon/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const kew::daemon::Config config = kew::daemon::parse_config(text, "fuzz.toml");
    // What the reader accepted obeys its own ranges.
    if (config.service.max_subscribers < 1 || config.http.max_connections < 1 ||
        config.service.silent_per_address < 1 || config.http.silent_per_address < 1 ||
        config.modbus.silent_per_address < 1)
      std::abort();
  } catch (const kew::config::ConfigError& e) {
    if (std::string_view(e.what()).empty()) std::abort();  // a refusal always says why
  }
  return 0;
}
