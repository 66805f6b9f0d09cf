#pragma once
// The configuration every kew tool shares (design §5.7): one TOML file whose
// [projection], [tracks], [kinetic], [probe], [alerts], [eligibility], [decoding],
// [[radar]], [[region]] and [regions] tables
// set up the pipeline and the decoders identically in kewd, kew-replay and the tools
// that replay recordings, so that a recording replayed with a daemon's file gives the
// daemon's alerts. Every key, its unit, range and default is documented in
// deploy/kew.toml.

#include <array>
#include <string>
#include <string_view>

#include "kew/config/config_error.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/formats.hpp"

namespace kew::config {

class Document;

/// Records in a batch when [pipeline] batch_records is not set (PipelineConfig).
inline constexpr std::size_t kDefaultBatchRecords = 512;

/// Records judged one by one after each flush when [pipeline] prompt_records is not set:
/// a live read of up to this many records sends each one's alerts as soon as it is
/// judged; the zones of a batch work in parallel only from about 24 records (design §3.3).
inline constexpr std::size_t kDefaultPromptRecords = 16;

struct SharedConfig {
  /// The service's defaults: PipelineConfig's, with every core, kDefaultBatchRecords and
  /// kDefaultPromptRecords; no aerodrome table yet (default_shared_config() loads it).
  SharedConfig();
  /// regions: the [[region]] tables, then [regions] geojson's; volumes: the [[volume]]
  /// tables, then [volumes] geojson's; eligibility.aerodromes: the table of
  /// aerodromes_file
  PipelineConfig pipeline;
  protocol::DecoderOptions decoding;  ///< radars of [[radar]], [decoding] limits
  /// The GeoJSON file of [regions] geojson, absolute; empty when none.
  std::string regions_geojson;
  /// The aerodrome table read into pipeline.eligibility.aerodromes, absolute: [eligibility]
  /// aerodromes_file, or default_aerodromes_file() (aerodromes.hpp); empty before reading.
  std::string aerodromes_file;
};

/// Top-level tables read into SharedConfig.
inline constexpr std::array<std::string_view, 13> kSharedSections = {
    "pipeline", "projection", "tracks", "kinetic", "probe",  "alerts", "eligibility",
    "decoding", "radar",      "region", "regions", "volume", "volumes"};
/// Top-level tables that only kewd reads (parsed in daemon/). Every other tool accepts a
/// kewd file and leaves them unread.
inline constexpr std::array<std::string_view, 7> kDaemonSections = {"service", "cat004", "modbus", "http", "nats",
                                                                   "input",   "notify"};

/// Reads the shared tables of `document`, after refusing any top-level key that is
/// neither a shared nor a kewd table, and loads the aerodrome table. Throws ConfigError
/// naming file and line (an aerodrome file's own line after the key's).
SharedConfig read_shared_config(const Document& document);
/// Loads the file at `path` and reads its shared tables. Throws ConfigError.
SharedConfig load_shared_config(const std::string& path);
/// What a tool runs with when given no file: every default, and the default aerodrome
/// table loaded. Throws ConfigError when that table cannot be read.
SharedConfig default_shared_config();

}  // namespace kew::config
