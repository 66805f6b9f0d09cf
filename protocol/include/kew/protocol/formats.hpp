#pragma once
// Every input format by name, auto-detection from a stream's first bytes, and one factory
// for all decoders. protocol/ reads no files: recordings are read by replay's
// RecordingReader, for kew-replay and kewd's file inputs alike.

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "kew/protocol/aircraft_json.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "kew/protocol/decoder.hpp"
#include "kew/util/name_table.hpp"

namespace kew::protocol {

enum class Format {
  Auto,                ///< detect from the first bytes (detect_format)
  Ndjson,              ///< canonical records, ndjson.hpp
  Sbs,                 ///< SBS-1 BaseStation, sbs.hpp
  OpenskyCsv,          ///< OpenSky state-vector CSV, opensky.hpp
  OpenskyJson,         ///< traffic-library state-vector JSON, opensky.hpp
  ReadsbJson,          ///< readsb JSON lines, readsb.hpp
  AircraftJson,        ///< aircraft.json snapshots, aircraft_json.hpp
  OpenskyRest,         ///< OpenSky REST API state vectors, opensky_rest.hpp
  ReadsbTrace,         ///< readsb trace files, readsb_trace.hpp
  AsterixRaw,          ///< ASTERIX data blocks back to back
  AsterixFinalFormat,  ///< ASTERIX in EUROCONTROL final format (.ff)
  AsterixPcap,         ///< ASTERIX in UDP datagrams of a pcap file
  AsterixDatagram,     ///< ASTERIX, one UDP datagram per feed() (live only)
};

/// The names of `format = ...` and `--format` (exact, lower case).
inline constexpr util::NameTable<Format, 13> kFormatNames({{
    {Format::Auto, "auto"},
    {Format::Ndjson, "ndjson"},
    {Format::Sbs, "sbs"},
    {Format::OpenskyCsv, "opensky-csv"},
    {Format::OpenskyJson, "opensky-json"},
    {Format::ReadsbJson, "readsb"},
    {Format::AircraftJson, "aircraft-json"},
    {Format::OpenskyRest, "opensky-rest"},
    {Format::ReadsbTrace, "readsb-trace"},
    {Format::AsterixRaw, "asterix-raw"},
    {Format::AsterixFinalFormat, "asterix-ff"},
    {Format::AsterixPcap, "asterix-pcap"},
    {Format::AsterixDatagram, "asterix-datagram"},
}});
constexpr std::string_view to_string(Format format) { return kFormatNames.name(format); }

struct DecoderOptions {
  AsterixOptions asterix;
  /// SbsOptions::utc_offset_s: receiver local time offset east of UTC, seconds.
  double sbs_utc_offset_s = 0;
  /// Longest line (text formats) or JSON array element (opensky-json), bytes.
  std::size_t max_line_bytes = 4096;
  /// JSON snapshots: their size limit and the oldest position reported; aircraft-json's,
  /// and opensky-rest's and readsb-trace's too (a trace uses only the size limit).
  AircraftJsonOptions aircraft_json;
};

/// Names the format of a stream from its first bytes (after gunzip when they start with
/// the gzip magic); Format::Auto when unknown. A few kilobytes suffice for the text
/// formats (the first non-comment lines are looked at); binary input is given to the
/// ASTERIX framing heuristics (pcap, final format, raw blocks; never datagram).
Format detect_format(std::span<const std::byte> head);

/// A decoder for `format`. For every format but AsterixDatagram, gzip input is inflated
/// transparently when the stream starts with the gzip magic. Format::Auto gives a
/// decoder that buffers the start of the stream (4 KiB, up to 64 KiB when that is not
/// enough), detects, then decodes; an unknown stream is counted "unknown_format" and
/// ignored until finish().
std::unique_ptr<Decoder> make_decoder(Format format, const DecoderOptions& options = {});

}  // namespace kew::protocol
