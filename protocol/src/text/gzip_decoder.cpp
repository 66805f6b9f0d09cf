// Streaming gzip in front of any decoder; described in gzip.hpp.
#include <fmt/format.h>
#include <zlib.h>

#include <array>
#include <limits>
#include <string>

#include "decoder_chain.hpp"
#include "kew/protocol/gzip.hpp"

namespace kew::protocol {
namespace {

constexpr unsigned char kMagic0 = 0x1f;
constexpr unsigned char kMagic1 = 0x8b;
// 16 + MAX_WBITS: gzip wrapper only (a zlib or raw deflate stream is corrupt here).
constexpr int kGzipWindowBits = 16 + MAX_WBITS;
constexpr std::size_t kOutputChunk = 64 * 1024;

/// zlib's stream state, released on destruction.
class Inflater {
 public:
  Inflater() { ok_ = inflateInit2(&stream_, kGzipWindowBits) == Z_OK; }
  ~Inflater() {
    if (ok_) inflateEnd(&stream_);
  }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  bool ok() const { return ok_; }
  z_stream& stream() { return stream_; }
  void reset() { inflateReset(&stream_); }

 private:
  z_stream stream_{};
  bool ok_ = false;
};

class GzipDecoder final : public Decoder {
 public:
  GzipDecoder(std::unique_ptr<Decoder> inner, GzipMode mode)
      : inner_(std::move(inner)), mode_(mode) {
    text::forward_rejections(*inner_, rejections());
    restart();
  }
  GzipDecoder(const GzipDecoder&) = delete;
  GzipDecoder& operator=(const GzipDecoder&) = delete;

  std::string_view format_name() const override { return inner_->format_name(); }
  std::size_t max_message_bytes() const override { return inner_->max_message_bytes(); }

  void feed(std::span<const std::byte> bytes, const ReportSink& sink) override {
    if (state_ == State::Sniffing) bytes = sniff(bytes, sink);
    switch (state_) {
      case State::PassThrough:
        inner_->feed(bytes, sink);
        break;
      case State::Inflating:
        inflate_bytes(bytes, sink);
        break;
      case State::Sniffing:
      case State::Stopped:
        break;
    }
    stream_offset_ += bytes.size();
  }

  void finish(const ReportSink& sink) override { end(false, sink); }
  void end_message(const ReportSink& sink) override { end(true, sink); }
  void set_receive_time(std::optional<double> utc_s) override { inner_->set_receive_time(utc_s); }

 private:
  enum class State { Sniffing, PassThrough, Inflating, Stopped };

  /// finish() (`message` false) or end_message(), passed on to the inner decoder.
  void end(bool message, const ReportSink& sink) {
    if (state_ == State::Sniffing && sniffed_ > 0) {
      // Too short to carry the magic: whatever it is, it is not gzip.
      inner_->feed(std::span<const std::byte>(sniff_buffer_.data(), sniffed_), sink);
    } else if (state_ == State::Inflating && in_member_) {
      rejections().reject("gzip_truncated",
                          fmt::format("gzip: stream ends inside a member ({} compressed bytes read)",
                                      stream_offset_));
    }
    if (message) inner_->end_message(sink);
    else inner_->finish(sink);
    restart();
  }

  void restart() {
    state_ = mode_ == GzipMode::Always ? State::Inflating : State::Sniffing;
    sniffed_ = 0;
    in_member_ = false;
    members_ended_ = 0;
    stream_offset_ = 0;
    if (inflater_.ok()) inflater_.reset();
    if (!inflater_.ok()) stop("zlib could not be initialised");
  }

  /// Collects the first two bytes to choose between inflating and passing through;
  /// returns what is left of `bytes` once decided (the sniffed bytes are already handled).
  std::span<const std::byte> sniff(std::span<const std::byte> bytes, const ReportSink& sink) {
    while (sniffed_ < sniff_buffer_.size() && !bytes.empty()) {
      sniff_buffer_[sniffed_++] = bytes.front();
      bytes = bytes.subspan(1);
    }
    if (sniffed_ < sniff_buffer_.size()) return bytes;
    const std::span<const std::byte> head(sniff_buffer_.data(), sniffed_);
    if (has_gzip_magic(head)) {
      state_ = State::Inflating;
      inflate_bytes(head, sink);
    } else {
      state_ = State::PassThrough;
      inner_->feed(head, sink);
    }
    return bytes;
  }

  void inflate_bytes(std::span<const std::byte> bytes, const ReportSink& sink) {
    z_stream& z = inflater_.stream();
    std::size_t offset = 0;
    while (offset < bytes.size() && state_ == State::Inflating) {
      if (!in_member_) {
        if (members_ended_ == 0 && static_cast<unsigned char>(bytes[offset]) != kMagic0) {
          stop("not a gzip stream");
          return;
        }
        if (static_cast<unsigned char>(bytes[offset]) != kMagic0) {
          rejections().reject("gzip_trailing_garbage",
                              fmt::format("gzip: {} bytes after the last member ignored",
                                          bytes.size() - offset));
          state_ = State::Stopped;
          return;
        }
        inflater_.reset();
        in_member_ = true;
      }
      // zlib counts in uInt; feed at most 1 GiB per call.
      const std::size_t take = std::min<std::size_t>(bytes.size() - offset, 1u << 30);
      z.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(bytes.data() + offset));
      z.avail_in = static_cast<uInt>(take);
      int status = Z_OK;
      while (true) {
        z.next_out = reinterpret_cast<Bytef*>(output_.data());
        z.avail_out = static_cast<uInt>(output_.size());
        status = inflate(&z, Z_NO_FLUSH);
        const std::size_t produced = output_.size() - z.avail_out;
        if (produced > 0) inner_->feed(std::span<const std::byte>(output_.data(), produced), sink);
        if (status != Z_OK) break;
        // A full output buffer may leave more output inside zlib even with no input left.
        if (z.avail_in == 0 && z.avail_out > 0) break;
      }
      offset += take - z.avail_in;
      if (status == Z_STREAM_END) {
        in_member_ = false;
        ++members_ended_;
      } else if (status != Z_OK && status != Z_BUF_ERROR) {
        stop(z.msg != nullptr ? z.msg : "inflate failed");
        return;
      }
    }
  }

  void stop(std::string_view why) {
    rejections().reject("gzip_corrupt", fmt::format("gzip: {} near compressed byte {}; rest of "
                                                    "the stream ignored", why, stream_offset_));
    state_ = State::Stopped;
  }

  std::unique_ptr<Decoder> inner_;
  GzipMode mode_;
  Inflater inflater_;
  State state_ = State::Sniffing;
  std::array<std::byte, 2> sniff_buffer_{};
  std::size_t sniffed_ = 0;
  bool in_member_ = false;           // inside a gzip member (header read, end not yet)
  std::uint64_t members_ended_ = 0;  // complete members so far in this stream
  std::uint64_t stream_offset_ = 0;  // compressed bytes fed before the current chunk
  std::array<std::byte, kOutputChunk> output_{};
};

}  // namespace

bool has_gzip_magic(std::span<const std::byte> head) {
  return head.size() >= 2 && static_cast<unsigned char>(head[0]) == kMagic0 &&
         static_cast<unsigned char>(head[1]) == kMagic1;
}

std::unique_ptr<Decoder> make_gzip_decoder(std::unique_ptr<Decoder> inner, GzipMode mode) {
  return std::make_unique<GzipDecoder>(std::move(inner), mode);
}

std::vector<std::byte> gunzip_prefix(std::span<const std::byte> compressed, std::size_t max_bytes) {
  std::vector<std::byte> out(max_bytes);
  Inflater inflater;
  if (!inflater.ok() || max_bytes == 0) return {};
  z_stream& z = inflater.stream();
  z.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(compressed.data()));
  z.avail_in = static_cast<uInt>(std::min<std::size_t>(compressed.size(), 1u << 30));
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(std::min<std::size_t>(max_bytes, 1u << 30));
  inflate(&z, Z_SYNC_FLUSH);
  out.resize(z.total_out);
  return out;
}

}  // namespace kew::protocol
