#pragma once
// ASTERIX track decoders (design §5.2): CAT062 system tracks, CAT048 monoradar target
// reports, CAT021 ADS-B reports, in four framings. protocol/docs/asterix.md describes
// every item used, the units and scalings, time handling and the CAT048 polar conversion.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

/// How ASTERIX data blocks are carried.
enum class AsterixFraming {
  /// Data blocks back to back (".ast" files, a TCP stream). format_name() "asterix-raw".
  RawBlocks,
  /// EUROCONTROL final format (".ff"): per frame a 16-bit frame length, board, line,
  /// day and 24-bit time, the data block(s), then A5A5A5A5. format_name() "asterix-ff".
  FinalFormat,
  /// Classic libpcap capture file of UDP datagrams carrying data blocks.
  /// format_name() "asterix-pcap".
  Pcap,
  /// Live UDP: each feed() call is exactly one datagram payload holding one or more
  /// data blocks. format_name() "asterix-datagram".
  Datagram,
};

/// A radar whose CAT048 polar plots are to be converted to WGS84.
struct RadarSite {
  std::uint8_t sac, sic;  ///< Data source identifier (I048/010) of the radar.
  double lat_deg;         ///< WGS84 latitude of the antenna, degrees [-90, 90].
  double lon_deg;         ///< WGS84 longitude of the antenna, degrees [-180, 180].
  double height_m;        ///< Antenna height above the WGS84 ellipsoid, metres.
};

struct AsterixOptions {
  /// Sites of the radars whose CAT048 reports are decoded; a CAT048 report from a radar
  /// not listed is rejected ("cat048_unknown_radar").
  std::vector<RadarSite> radars;
  /// UTC midnight (Unix seconds) of the day the first record belongs to. ASTERIX carries
  /// only the time of day; the decoder moves to the next day when the time of day jumps
  /// back by more than 12 h within the stream.
  double day_start_utc_s = 0;
  /// Pcap framing only: take the UTC day from each packet's capture timestamp instead of
  /// day_start_utc_s (the record's time of day is placed within ±12 h of the capture time).
  bool day_from_pcap = true;
};

/// Makes a decoder for one framing. Every decoder keeps the Decoder contract
/// (incremental, bounded, resynchronising, rejections counted by reason).
std::unique_ptr<Decoder> make_asterix_decoder(AsterixFraming framing, AsterixOptions options = {});

/// Heuristic used by format auto-detection: 0..1 confidence that `head` (first bytes of a file) is this framing.
/// Pcap: the file magic. FinalFormat: frames whose A5A5A5A5 trailer sits where the frame
/// length says, holding a chain of data blocks. RawBlocks: consecutive plausible block
/// headers. Scores are listed in protocol/docs/asterix.md §6. Datagram: half the RawBlocks
/// score, since a file is never datagram-framed but a captured datagram looks the same.
double asterix_framing_confidence(AsterixFraming framing, std::span<const std::byte> head);

}  // namespace kew::protocol
