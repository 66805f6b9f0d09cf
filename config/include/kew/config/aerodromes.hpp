#pragma once
// The aerodrome table of [eligibility] aerodromes_file (design §4.5, data/README.md):
// found, read and parsed here, so that core stays without I/O. Every tool that runs the
// pipeline, and kew-gen's global scenario, takes its table from here.

#include <cstddef>
#include <memory>
#include <string>

#include "kew/config/config_error.hpp"
#include "kew/eligibility/aerodromes.hpp"

namespace kew::config {

/// Largest aerodrome file read, bytes (16 MiB: OurAirports' whole airports.csv is about
/// 12 MB; kew's table is about 230 KB).
inline constexpr std::size_t kMaxAerodromeFileBytes = std::size_t{16} << 20;

/// The table read when [eligibility] aerodromes_file is "" or absent: data/aerodromes.csv
/// of the source tree for a program of the build tree (tests, a developer's run), else
/// share/kew/aerodromes.csv of the installation the program runs from (its bin/'s
/// ../share/kew; /usr/share/kew for the Debian package). Absolute.
std::string default_aerodromes_file();

/// load_aerodromes(default_aerodromes_file()), its errors saying that the file is the
/// default of [eligibility] aerodromes_file: a program's table when it reads no
/// configuration file but runs the pipeline or the global scenario (benchmarks, tests).
std::shared_ptr<const eligibility::AerodromeTable> load_default_aerodromes();

/// The aerodrome table of the CSV file at `path` (kew/eligibility/aerodrome_csv.hpp).
/// Throws ConfigError "path:line: message" for a malformed row, or naming the file when
/// it cannot be read or is larger than kMaxAerodromeFileBytes. The file read last is
/// parsed once per version (its size and modification time): reading it again returns
/// the same table, until the file is replaced or edited.
std::shared_ptr<const eligibility::AerodromeTable> load_aerodromes(const std::string& path);

}  // namespace kew::config
