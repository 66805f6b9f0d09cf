#pragma once
// Decodes complete ASTERIX data blocks into TrackReports, whatever framing carried them.

#include <cstddef>
#include <cstdint>
#include <optional>

#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "kew/protocol/asterix/day_clock.hpp"
#include "kew/protocol/asterix/radar_projection.hpp"
#include "kew/protocol/asterix/record_walker.hpp"
#include "record_context.hpp"

namespace kew::protocol::asterix {

/// True for category numbers EUROCONTROL has assigned (a block of any other category is
/// taken as garbage when resynchronising).
bool is_assigned_category(std::uint8_t category);

/// Categories kew decodes into reports (021, 048, 062).
bool is_decoded_category(std::uint8_t category);

class BlockDecoder {
 public:
  BlockDecoder(const AsterixOptions& options, Rejections& rejections);

  /// Decodes one data block of `size` bytes (category, 16-bit length equal to `size`,
  /// records). A record that cannot be walked ends the block (counted); blocks of
  /// categories kew does not decode are counted "asterix_category_ignored".
  void decode_block(const std::uint8_t* block, std::size_t size, const ReportSink& sink);

  /// Decodes the data blocks filling a datagram or a final-format frame payload. A block
  /// length that is impossible there ends the payload ("asterix_bad_block_length").
  void decode_blocks(const std::uint8_t* payload, std::size_t size, const ReportSink& sink);

  /// True when `block` (a complete data block of a category kew decodes) splits exactly
  /// into records that walk under its UAP, trailing zero padding allowed. Framings use it
  /// as evidence that a block header found after garbage is real.
  bool walks_cleanly(const std::uint8_t* block, std::size_t size);

  /// Pcap: the capture time (UTC s) of the packet whose blocks follow; see DayClock.
  void set_capture_time(std::optional<double> capture_utc_s) { clock_.set_capture_time(capture_utc_s); }

 private:
  void decode_records(const Uap& uap, bool (*decode)(const RecordItems&, RecordContext&, TrackReport&),
                      const std::uint8_t* block, std::size_t size, const ReportSink& sink);
  /// True when the block fits the CAT021 0.26 profile and not the 2.x one.
  bool block_is_cat021_v026(const std::uint8_t* block, std::size_t size);
  /// True when every record of `block` walks under `uap` and carries FRN 1 (the data source
  /// identifier, mandatory in every category kew decodes), up to the end of the block.
  bool records_fit(const Uap& uap, const std::uint8_t* block, std::size_t size);

  Rejections& rejections_;
  DayClock clock_;
  RadarProjector radars_;
  RecordItems items_;
  TrackReport report_;
};

}  // namespace kew::protocol::asterix
