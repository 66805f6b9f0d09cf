#pragma once
// kewd's inputs, one class per transport (design §5.7 [[input]]): UDP (unicast or
// multicast), TCP client with reconnect and backoff, TCP server, NATS (src/nats), a watched file
// read again whenever it is replaced (watched_file_input.cpp), file (through replay's
// RecordingReader and Pacer, as kew-replay reads recordings). Every byte
// stream gets its own decoder (one per TCP connection), so streams never mix; decoded
// reports go to the service's handler on the I/O thread.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "source_state.hpp"
#include "kew/daemon/config.hpp"
#include "kew/protocol/decoder.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"

namespace kew::daemon {

class Input {
 public:
  using ReportHandler = std::function<void(const TrackReport&)>;
  virtual ~Input() = default;
  virtual void start() = 0;
  /// Closes sockets and files; pending handlers finish with operation_aborted.
  virtual void stop() = 0;
  const InputConfig& config() const { return config_; }
  /// Called once when a file input has read its file to the end (or could not open it);
  /// other inputs never end.
  void set_end_handler(std::function<void()> handler) { end_handler_ = std::move(handler); }
  /// Hot standby (design §5.9): before start(), read the feed from this message of its
  /// JetStream stream (the pair's origin), whatever this input's durable consumer had
  /// taken before. Only a NATS input with `durable` and `stream` can; false for the others.
  virtual bool read_from_stream_sequence(std::uint64_t /*sequence*/) { return false; }
  /// Hot standby's checkpoint (design §5.9), on the I/O thread: the JetStream stream
  /// sequence of the last message whose records have all been delivered; nullopt before
  /// the first, and for every input but a NATS input with `durable`.
  virtual std::optional<std::uint64_t> delivered_stream_sequence() const { return std::nullopt; }
  /// Called on the I/O thread when an input that knows its source's backlog (a durable
  /// JetStream consumer) learns its source's state, ordered with the records it delivers;
  /// other inputs never call it (their source counts as caught up).
  void set_source_handler(std::function<void(SourceState)> handler) { source_handler_ = std::move(handler); }
  /// The port actually bound (servers and UDP; useful with port 0 in tests).
  virtual std::uint16_t bound_port() const { return 0; }
  /// Figures so far; `rejected` holds ended streams' and the open streams' rejections.
  protocol::InputStatistics statistics() const {
    protocol::InputStatistics s = figures_;
    s.name = config_.name;
    s.datagrams_dropped = datagrams_dropped();
    add_open_stream_rejections(s.rejected);
    add_live_figures(s);
    return s;
  }
  /// UDP: datagrams the kernel dropped before kewd could read them (its receive buffer
  /// was full), as known so far; other transports lose none there.
  virtual std::uint64_t datagrams_dropped() const { return 0; }

 protected:
  Input(InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : config_(std::move(config)), options_(std::move(options)), handler_(std::move(handler)) {}
  /// The decoder options of this input (its ASTERIX data day).
  protocol::DecoderOptions stream_options() const;
  /// Sends the messages of `rejections` to the log, naming this input (rate-limited).
  void log_rejections(Rejections& rejections) const;
  /// A fresh decoder for one stream, its rejections logged and merged into
  /// figures_.rejected when the stream ends (see retire()).
  std::unique_ptr<protocol::Decoder> make_stream_decoder();
  /// Feeds bytes to a stream's decoder and forwards its reports.
  void feed(protocol::Decoder& decoder, const void* data, std::size_t n);
  /// Feeds one datagram, a whole message decoded alone: nothing of it (a line without its
  /// newline, a skipped over-long line) reaches the next datagram or another sender.
  void feed_message(protocol::Decoder& decoder, const void* data, std::size_t n);
  /// Ends a stream: flushes the decoder and keeps its rejection counts.
  void retire(protocol::Decoder& decoder);
  virtual void add_open_stream_rejections(Rejections&) const {}
  /// Figures kept outside figures_ (by another thread's client library).
  virtual void add_live_figures(protocol::InputStatistics&) const {}
  /// Counts a decoded report and hands it to the service.
  void deliver(const TrackReport& report);

  InputConfig config_;
  protocol::DecoderOptions options_;
  ReportHandler handler_;
  std::function<void()> end_handler_;
  std::function<void(SourceState)> source_handler_;
  /// `rejected`: the rejections of streams that ended; `name` is filled by statistics().
  protocol::InputStatistics figures_;
};

/// Builds the input of `config` on `io`. `listen_any` widens loopback server binds.
std::unique_ptr<Input> make_input(boost::asio::io_context& io, const InputConfig& config,
                                  const protocol::DecoderOptions& options, Input::ReportHandler handler);

/// For the log at start: "input NAME: FORMAT TRANSPORT ADDRESS (port P)".
std::string describe(const Input& input);

}  // namespace kew::daemon
