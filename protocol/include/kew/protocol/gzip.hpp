#pragma once
// Transparent gzip (RFC 1952) in front of any decoder: zlib inflate, streaming, so a
// compressed recording of any size is decoded in bounded memory (zlib's 32 KiB window
// plus a 64 KiB output buffer).
//
// Concatenated gzip members (what `cat a.gz b.gz` and pigz produce) are decoded one
// after the other. Rejection reasons, counted on the wrapper (the inner decoder's
// reasons are forwarded there too, so the wrapper's rejections() is the whole story):
//   gzip_corrupt           inflate failed (not gzip, bad header, bad data, bad CRC):
//                          the rest of the stream is ignored until finish(). Deflate
//                          data has no check before the member's CRC, so bytes inflated
//                          between damage and its detection may be wrong (the inner
//                          decoder's own checks are the guard there)
//   gzip_trailing_garbage  bytes after a complete member that do not start another
//                          one (e.g. zero padding): ignored
//   gzip_truncated         finish() in the middle of a member

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol {

enum class GzipMode {
  Always,     ///< the stream must be gzip; anything else is gzip_corrupt
  WhenMagic,  ///< inflate when the stream starts with 1f 8b, else pass bytes through
};

/// True when `head` starts with the gzip magic bytes 1f 8b.
bool has_gzip_magic(std::span<const std::byte> head);

/// Wraps `inner`: feed() takes the (possibly) compressed stream and passes the inflated
/// bytes to `inner`. format_name() and max_message_bytes() are the inner decoder's.
std::unique_ptr<Decoder> make_gzip_decoder(std::unique_ptr<Decoder> inner,
                                           GzipMode mode = GzipMode::WhenMagic);

/// Inflates as much of the start of a gzip stream as `compressed` holds (a file's first
/// kilobytes), at most `max_bytes` of output; stops quietly at the end of the input or
/// at an error. For format detection.
std::vector<std::byte> gunzip_prefix(std::span<const std::byte> compressed,
                                     std::size_t max_bytes);

}  // namespace kew::protocol
