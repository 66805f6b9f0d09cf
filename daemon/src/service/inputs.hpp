#pragma once
// kewd's inputs, one class per transport (SPEC §5.7 [[input]]): UDP (unicast or
// multicast), TCP client with reconnect and backoff, TCP server, file. Every byte
// stream gets its own decoder (one per TCP connection), so streams never mix; decoded
// reports go to the service's handler on the I/O thread.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "kew/daemon/config.hpp"
#include "kew/protocol/decoder.hpp"

namespace kew::daemon {

struct InputFigures {
  std::uint64_t bytes = 0;
  std::uint64_t reports = 0;
  std::uint64_t connections = 0;        ///< accepted (server) or established (client)
  std::uint64_t connections_refused = 0;///< over max_connections
  std::uint64_t oversized_datagrams = 0;
  Rejections rejections;                ///< decoder rejections of all this input's streams
};

class Input {
 public:
  using ReportHandler = std::function<void(const TrackReport&)>;
  virtual ~Input() = default;
  virtual void start() = 0;
  /// Closes sockets and files; pending handlers finish with operation_aborted.
  virtual void stop() = 0;
  const InputConfig& config() const { return config_; }
  const InputFigures& figures() const { return figures_; }
  /// The port actually bound (servers and UDP; useful with port 0 in tests).
  virtual std::uint16_t bound_port() const { return 0; }
  /// Every rejection so far: ended streams' and the open streams' decoders'.
  Rejections rejections() const {
    Rejections all;
    all.merge(figures_.rejections);
    add_open_stream_rejections(all);
    return all;
  }

 protected:
  Input(InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : config_(std::move(config)), options_(std::move(options)), handler_(std::move(handler)) {}
  /// A fresh decoder for one stream, its rejections reported to the log (rate-limited)
  /// and merged into figures() when the stream ends (see retire()).
  std::unique_ptr<protocol::Decoder> make_stream_decoder();
  /// Feeds bytes to a stream's decoder and forwards its reports.
  void feed(protocol::Decoder& decoder, const void* data, std::size_t n);
  /// Ends a stream: flushes the decoder and keeps its rejection counts.
  void retire(protocol::Decoder& decoder);
  virtual void add_open_stream_rejections(Rejections&) const {}

  InputConfig config_;
  protocol::DecoderOptions options_;
  ReportHandler handler_;
  InputFigures figures_;
};

/// Builds the input of `config` on `io`. `listen_any` widens loopback server binds.
std::unique_ptr<Input> make_input(boost::asio::io_context& io, const InputConfig& config,
                                  const protocol::DecoderOptions& options, Input::ReportHandler handler);

}  // namespace kew::daemon
