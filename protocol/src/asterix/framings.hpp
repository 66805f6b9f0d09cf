#pragma once
// Factories and auto-detection evidence of each framing (asterix_decoder.cpp dispatches).

#include <cstdint>
#include <memory>
#include <span>

#include "kew/protocol/asterix/asterix_decoder.hpp"

namespace kew::protocol::asterix {

/// Largest data block (its length field is 16 bits).
inline constexpr std::size_t kMaxBlockBytes = 65535;

std::unique_ptr<Decoder> make_raw_blocks_decoder(const AsterixOptions& options);
std::unique_ptr<Decoder> make_final_format_decoder(const AsterixOptions& options);
std::unique_ptr<Decoder> make_pcap_decoder(const AsterixOptions& options);

double raw_blocks_confidence(std::span<const std::uint8_t> head);
double final_format_confidence(std::span<const std::uint8_t> head);
double pcap_confidence(std::span<const std::uint8_t> head);

/// A data block header that could start a real block: an assigned category and a length
/// that leaves room for at least one record (>= 4 bytes).
bool plausible_block_header(std::uint8_t category, std::size_t length);

}  // namespace kew::protocol::asterix
