#pragma once
// Big-endian field access for ASTERIX items and network headers, and little/big-endian
// access for pcap headers. Callers check lengths before reading.

#include <cstddef>
#include <cstdint>
#include <span>

namespace kew::protocol::asterix {

inline std::uint32_t be16(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 8) | p[1];
}
inline std::uint32_t be24(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
}
inline std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         p[3];
}
inline std::uint32_t le32(const std::uint8_t* p) {
  return (std::uint32_t{p[3]} << 24) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[1]} << 8) |
         p[0];
}

/// Two's complement value of the low `bits` bits of `raw`.
inline std::int32_t sign_extend(std::uint32_t raw, unsigned bits) {
  const std::uint64_t modulus = std::uint64_t{1} << bits;
  const auto value = static_cast<std::int64_t>(raw & (modulus - 1));
  const bool negative = (value >> (bits - 1)) != 0;
  return static_cast<std::int32_t>(negative ? value - static_cast<std::int64_t>(modulus) : value);
}

inline const std::uint8_t* as_uint8(std::span<const std::byte> bytes) {
  return reinterpret_cast<const std::uint8_t*>(bytes.data());
}

}  // namespace kew::protocol::asterix
