#pragma once
// What every text-decoder fuzz target does with its input: the first 4 bytes choose up
// to 3 chunk boundaries, the rest is the stream. It is decoded twice, chunked and in one
// piece; both must give the same reports and rejection counts (the Decoder contract),
// and every report must keep the decoders' contract (check_report below).
// Any violation traps, which libFuzzer reports as a crash with the input.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol::fuzz {

/// True when a track angle is as check_report() leaves it: within [0, 360), or further
/// than one turn from it (passed on for the track table to drop, design §4.3).
inline bool track_angle_settled(double deg) {
  const bool within_one_turn = deg >= -360.0 && deg < 720.0;
  return !within_one_turn || (deg >= 0.0 && deg < 360.0);
}

/// The text decoders' contract: the required fields are valid; an optional velocity field
/// passes as the source gave it (the track table drops one out of range), except that a
/// track angle within one turn is brought into [0, 360); a Mode 3/A code is 12 bits.
inline void check_report(const TrackReport& r) {
  const bool valid = !r.id.empty() && std::isfinite(r.t) && r.lat_deg >= -90.0 &&
                     r.lat_deg <= 90.0 && r.lon_deg >= -180.0 && r.lon_deg <= 180.0 &&
                     std::isfinite(r.alt_ft) && (!r.trk_deg || track_angle_settled(*r.trk_deg)) &&
                     (!r.mode3a || *r.mode3a <= 07777);
  if (!valid) __builtin_trap();
}

struct Outcome {
  std::size_t reports = 0;
  double checksum = 0;  // sum of times and positions: same reports, same sum
  std::map<std::string, std::uint64_t, std::less<>> rejections;
};

inline Outcome decode(Decoder& decoder, std::span<const std::byte> stream,
                      const std::vector<std::size_t>& cuts) {
  Outcome outcome;
  const ReportSink sink = [&](const TrackReport& r) {
    check_report(r);
    ++outcome.reports;
    outcome.checksum += r.t + r.lat_deg + r.lon_deg + r.alt_ft;
  };
  std::size_t start = 0;
  for (const std::size_t cut : cuts) {
    decoder.feed(stream.subspan(start, cut - start), sink);
    start = cut;
  }
  decoder.feed(stream.subspan(start), sink);
  decoder.finish(sink);
  outcome.rejections = decoder.rejections().by_reason();
  return outcome;
}

/// Runs `make()`'s decoder over the fuzz input as described above.
template <class MakeDecoder>
void fuzz_decoder(const std::uint8_t* data, std::size_t size, MakeDecoder make) {
  constexpr std::size_t kControl = 4;
  if (size < kControl) return;
  const auto stream = std::as_bytes(std::span<const std::uint8_t>(data + kControl, size - kControl));
  std::vector<std::size_t> cuts;
  const std::size_t cut_count = data[0] % 4;
  for (std::size_t i = 0; i < cut_count; ++i)
    cuts.push_back(stream.empty() ? 0 : (static_cast<std::size_t>(data[1 + i]) * 257u) % (stream.size() + 1));
  std::sort(cuts.begin(), cuts.end());
  const std::unique_ptr<Decoder> chunked = make();
  const Outcome a = decode(*chunked, stream, cuts);
  const std::unique_ptr<Decoder> whole = make();
  const Outcome b = decode(*whole, stream, {});
  const bool same_checksum = a.checksum == b.checksum || (std::isnan(a.checksum) && std::isnan(b.checksum));
  if (a.reports != b.reports || !same_checksum || a.rejections != b.rejections) __builtin_trap();
  // A decoder is reusable after finish(): the same stream again gives the same outcome.
  const Outcome again = decode(*whole, stream, {});
  if (again.reports != b.reports) __builtin_trap();
}

}  // namespace kew::protocol::fuzz
