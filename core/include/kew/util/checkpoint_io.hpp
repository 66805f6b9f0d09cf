#pragma once
// The byte form of a checkpoint of kew's computation (design §5.9): what a hot-standby
// pair's restarted instance loads instead of replaying the feed from the pair's origin.
// Integers little-endian at their width, doubles by their IEEE-754 bits (so a restored
// value is the very value saved: signs of zero, infinities and NaN included), booleans
// one byte (0 or 1), text as a 32-bit length and its bytes. A checkpoint restores into
// the same computation only if it is read exactly as written: the reader refuses any
// truncation or malformed value by throwing CheckpointError with the byte offset.

#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace kew::util {

/// A checkpoint that cannot be read: truncated, or a value out of its range.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CheckpointWriter {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void u16(std::uint16_t v) { little_endian(v, 2); }
  void u32(std::uint32_t v) { little_endian(v, 4); }
  void u64(std::uint64_t v) { little_endian(v, 8); }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    u64(bits);
  }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void text(std::string_view v) {
    u32(static_cast<std::uint32_t>(v.size()));
    bytes_.append(v);
  }
  /// Whether `v` holds a value, then the value written by `write(value)`.
  template <class T, class Write>
  void optional(const std::optional<T>& v, Write write) {
    boolean(v.has_value());
    if (v) write(*v);
  }
  /// A section's name, so that a reader out of step fails where it went wrong.
  void tag(std::string_view name) { text(name); }
  /// A section's name and the version of its layout (CheckpointReader::section).
  void section(std::string_view name, std::uint32_t version) {
    tag(name);
    u32(version);
  }

  /// One value by its type, as CheckpointReader::field reads it back: a class writes and
  /// reads its state with one template of field() calls, so the two cannot drift apart.
  void field(std::uint8_t v) { u8(v); }
  void field(std::uint16_t v) { u16(v); }
  void field(std::uint32_t v) { u32(v); }
  void field(std::uint64_t v) { u64(v); }
  void field(std::int32_t v) { i32(v); }
  void field(double v) { f64(v); }
  void field(bool v) { boolean(v); }
  void field(const std::string& v) { text(v); }
  /// An enumeration as its underlying byte (`last`: for the reader).
  template <class E>
  void field(E v, E /*last*/) {
    u8(static_cast<std::uint8_t>(v));
  }
  template <class T>
  void field(const std::optional<T>& v) {
    boolean(v.has_value());
    if (v) field(*v);
  }

  const std::string& bytes() const { return bytes_; }
  std::string take() { return std::move(bytes_); }

 private:
  void little_endian(std::uint64_t v, int width) {
    for (int i = 0; i < width; ++i) bytes_.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
  }
  std::string bytes_;
};

class CheckpointReader {
 public:
  explicit CheckpointReader(std::string_view bytes) : bytes_(bytes) {}

  std::uint8_t u8() { return static_cast<std::uint8_t>(little_endian(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(little_endian(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(little_endian(4)); }
  std::uint64_t u64() { return little_endian(8); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  double f64() {
    const std::uint64_t bits = u64();
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  bool boolean() {
    const std::size_t at = offset_;
    const std::uint8_t v = u8();
    if (v > 1) fail(at, "a boolean that is neither 0 nor 1");
    return v == 1;
  }
  std::string text() {
    const std::uint32_t size = u32();
    need(size);
    std::string v(bytes_.substr(offset_, size));
    offset_ += size;
    return v;
  }
  template <class T, class Read>
  std::optional<T> optional(Read read) {
    if (!boolean()) return std::nullopt;
    return read();
  }
  /// An enumeration written as its underlying byte, refused above `last`.
  template <class E>
  E enumeration(E last) {
    const std::size_t at = offset_;
    const std::uint8_t v = u8();
    if (v > static_cast<std::uint8_t>(last)) fail(at, "an enumeration value out of range");
    return static_cast<E>(v);
  }
  /// One value by its type (CheckpointWriter::field).
  void field(std::uint8_t& v) { v = u8(); }
  void field(std::uint16_t& v) { v = u16(); }
  void field(std::uint32_t& v) { v = u32(); }
  void field(std::uint64_t& v) { v = u64(); }
  void field(std::int32_t& v) { v = i32(); }
  void field(double& v) { v = f64(); }
  void field(bool& v) { v = boolean(); }
  void field(std::string& v) { v = text(); }
  template <class E>
  void field(E& v, E last) {
    v = enumeration(last);
  }
  template <class T>
  void field(std::optional<T>& v) {
    v.reset();
    if (!boolean()) return;
    T value{};
    field(value);
    v = value;
  }
  /// The section `name` begins here.
  void tag(std::string_view name) {
    const std::size_t at = offset_;
    if (text() != name) fail(at, "not the section " + std::string(name));
  }

  /// The section `name` of layout `version` begins here: another version is refused.
  void section(std::string_view name, std::uint32_t version) {
    tag(name);
    const std::size_t at = offset_;
    if (u32() != version) fail(at, std::string(name) + " of another version");
  }

  bool at_end() const { return offset_ == bytes_.size(); }
  std::size_t offset() const { return offset_; }
  [[noreturn]] void fail(std::size_t at, const std::string& what) const {
    throw CheckpointError("checkpoint byte " + std::to_string(at) + ": " + what);
  }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - offset_ < n) fail(offset_, "truncated");
  }
  std::uint64_t little_endian(int width) {
    need(static_cast<std::size_t>(width));
    std::uint64_t v = 0;
    for (int i = 0; i < width; ++i)
      v |= std::uint64_t{static_cast<unsigned char>(bytes_[offset_ + static_cast<std::size_t>(i)])} << (8 * i);
    offset_ += static_cast<std::size_t>(width);
    return v;
  }

  std::string_view bytes_;
  std::size_t offset_ = 0;
};

}  // namespace kew::util
