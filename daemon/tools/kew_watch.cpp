// kew-watch (design §5.6): a subscriber of kewd's alert stream, or (--nats, design §5.9)
// of the alerts kewd publishes on NATS, from JetStream from a given seq on. Prints one
// readable line per alert event (or the raw JSON lines with --json), like gpsd's
// cgps/gpspipe.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "kew/config/address.hpp"
#include "kew/config/nats_servers.hpp"
#include "nats_connection.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/protocol/utc_text.hpp"
#include "kew/protocol/version.hpp"
#include "kew/util/units.hpp"

namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using kew::protocol::StreamObjectClass;

constexpr int kUsageError = 64;
constexpr int kConnectionFailed = 1;
constexpr int kSubscribeAttempts = 10;  // --nats: JetStream calls, each waiting up to 5 s
using kew::units::kMetresPerNauticalMile;

struct Flags {
  std::string address = "127.0.0.1:4747";
  std::string min_severity = "caution";
  long count = 0;  // 0: until the server closes
  bool json = false;
  bool alive = false;
  bool tracks = false;
  std::string nats_url;             // --nats: read the JetStream stream instead
  std::string stream = "KEW_ALERTS";
  std::optional<std::uint64_t> since;
};

std::string party(const kew::AlertParty& p) {
  const std::string level = std::isfinite(p.alt_ft) ? fmt::format("FL{:03.0f}", p.alt_ft / 100.0) : "FL---";
  return fmt::format("{} {:<8} {}", p.id, p.callsign.empty() ? "-" : p.callsign, level);
}

std::string state_name(const kew::AlertEvent& e) {
  switch (e.state) {
    case kew::AlertState::New: return "NEW";
    case kew::AlertState::Update: return "UPDATE";
    case kew::AlertState::End: return "END";
  }
  return "?";
}

/// An area proximity warning: the aircraft, the volume and when it enters, in place of
/// the pair and its closest approach.
std::string area_warning(const kew::AlertEvent& e) {
  std::string text = fmt::format("{} → {}", party(e.a), e.volume);
  if (!e.volume_kind.empty()) text += fmt::format(" ({})", e.volume_kind);
  if (e.state == kew::AlertState::End) return text;
  if (e.severity == kew::Severity::Loss || e.t_los_s <= 0) return text + "  inside now";
  return text + fmt::format("  entry in {:.0f} s", e.t_los_s);
}

void print_alert(const kew::AlertEvent& e, const char* state) {
  std::string line = fmt::format("{} {:<6} {:<7} ", kew::protocol::utc_time_of_day(e.t), state, kew::to_string(e.severity));
  if (e.kind == kew::AlertKind::Apw) line += area_warning(e);
  else line += fmt::format("{} x {}", party(e.a), party(e.b));
  if (e.kind == kew::AlertKind::Stca && e.state != kew::AlertState::End) {
    line += fmt::format("  t_los {:>3.0f} s  cpa {:.1f} NM {:.0f} ft in {:.0f} s", e.t_los_s, e.cpa_h_m / kMetresPerNauticalMile,
                        e.cpa_v_ft, e.t_cpa_s);
    line += fmt::format("  by {}", kew::to_string(e.hypothesis));
  }
  if (!e.region.empty()) line += fmt::format("  region {}", e.region);
  if (e.acknowledged) line += "  ack";
  std::printf("%s  [%s]\n", line.c_str(), e.id.c_str());
}

enum class Shown { Alert, ServerError, Other };

/// Prints the object `reader` has just read from `line` as `flags` ask.
Shown show(const Flags& flags, const kew::protocol::AlertStreamReader& reader, const std::string& line,
           const std::string& origin) {
  const StreamObjectClass kind = reader.object_class();
  if (flags.json) {
    std::fputs(line.c_str(), stdout);
  } else if (kind == StreamObjectClass::Version) {
    std::printf("connected to kewd %s (%s, protocol %d) at %s\n", reader.text().c_str(),
                reader.revision().empty() ? "revision unknown" : reader.revision().c_str(), reader.proto(),
                origin.c_str());
  } else if (kind == StreamObjectClass::Start) {
    // kewd (re)started: a new run id; alerts open before it ended with reason "restart".
    std::printf("START  kewd %s run %s started %s\n", reader.text().c_str(), reader.run().c_str(),
                kew::protocol::utc_time_of_day(reader.start_t()).c_str());
  } else if (kind == StreamObjectClass::Alerts) {
    std::printf("%zu active alerts\n", reader.alerts().size());
    for (const kew::AlertEvent& e : reader.alerts()) print_alert(e, "ACTIVE");
  } else if (kind == StreamObjectClass::Alert) {
    print_alert(reader.alert(), state_name(reader.alert()).c_str());
  } else if (kind == StreamObjectClass::Ack) {
    std::printf("ACK    %zu alerts acknowledged through %s by %s\n", reader.acknowledged().size(),
                reader.text().c_str(),
                reader.acknowledging_client().empty() ? "?" : reader.acknowledging_client().c_str());
  } else if (kind == StreamObjectClass::Alive && flags.alive) {
    const auto& a = reader.alive();
    const std::string health =
        a.degraded() ? ", degraded: " + std::string(kew::protocol::kHealthReasonNames.name(a.health)) : "";
    std::printf("%s ALIVE  %llu tracks, %llu alerts, %.0f records/s%s\n",
                a.last_data_t ? kew::protocol::utc_time_of_day(*a.last_data_t).c_str() : "--:--:--", static_cast<unsigned long long>(a.tracks),
                static_cast<unsigned long long>(a.alerts), a.records_per_s, health.c_str());
  }
  if (kind == StreamObjectClass::Error) {
    std::fprintf(stderr, "kew-watch: server error: %s\n", reader.text().c_str());
    return Shown::ServerError;
  }
  return kind == StreamObjectClass::Alert ? Shown::Alert : Shown::Other;
}

/// The first sequence number of `stream` whose message has a Kew-Seq above `since`:
/// kewd's seq never decreases along the stream (it continues across restarts through its
/// state directory), so a binary search finds it. Past the last message: last + 1.
std::uint64_t first_after(jsCtx* js, const std::string& stream, std::uint64_t since) {
  jsStreamInfo* info = nullptr;
  kew::nats::check(js_GetStreamInfo(&info, js, stream.c_str(), nullptr, nullptr), "JetStream stream " + stream);
  std::uint64_t low = info->State.FirstSeq, high = info->State.LastSeq + 1;
  jsStreamInfo_Destroy(info);
  if (low == 0) return 1;  // an empty stream
  while (low < high) {
    const std::uint64_t middle = low + (high - low) / 2;
    // A message that cannot be read would send the search the wrong way: an error.
    const std::uint64_t seq = kew::nats::kept_seq(js, stream, middle);
    if (seq > since) high = middle;
    else low = middle + 1;
  }
  return low;
}

/// The Kew-Lease header of a message (0: none, not hot standby).
std::uint64_t fencing_token(natsMsg* message) {
  const char* value = nullptr;
  if (natsMsgHeader_Get(message, kew::nats::kLeaseHeader, &value) != NATS_OK) return 0;
  return std::strtoull(value, nullptr, 10);
}

/// As kewd's stream filters a ?WATCH: an alert opened while reading is shown from its
/// first event at or above `min_severity`, then to its end. An alert opened before the
/// first message read (before --since's seq, or before kew-watch started) may have been
/// shown to the reader already: its End is always shown, and its updates are as those of
/// an alert opened here.
bool passes_filter(const kew::AlertEvent& e, kew::Severity min_severity, std::set<std::string>& shown,
                   std::set<std::string>& hidden) {
  if (e.state == kew::AlertState::New) {
    if (e.severity >= min_severity) shown.insert(e.id);
    else hidden.insert(e.id);
    return e.severity >= min_severity;
  }
  const bool opened_here_unshown = hidden.contains(e.id);
  if (e.state == kew::AlertState::End) {
    shown.erase(e.id);
    hidden.erase(e.id);
    return !opened_here_unshown;
  }
  if (shown.contains(e.id)) return true;
  if (e.severity < min_severity) return false;
  hidden.erase(e.id);
  shown.insert(e.id);
  return true;
}

/// kew-watch --nats: the alert events and acknowledgements of `flags.stream`, from the
/// first after --since (or those published from now on), until -n is reached.
int watch_nats(const Flags& flags) {
  std::string error;
  const std::optional<std::vector<std::string>> servers = kew::config::parse_nats_servers(flags.nats_url, &error);
  if (!servers) {
    std::fprintf(stderr, "kew-watch: --nats %s\n", error.c_str());
    return kUsageError;
  }
  try {
    kew::nats::NatsConnection connection(*servers, "kew-watch", [](std::string_view event) {
      std::fprintf(stderr, "kew-watch: %.*s\n", static_cast<int>(event.size()), event.data());
    });
    jsSubOptions options;
    jsSubOptions_Init(&options);
    options.Stream = flags.stream.c_str();
    options.Ordered = true;  // in stream order, gaps refilled by the client
    if (flags.since) {
      options.Config.DeliverPolicy = js_DeliverByStartSequence;
      options.Config.OptStartSeq = first_after(connection.jetstream(), flags.stream, *flags.since);
    } else {
      options.Config.DeliverPolicy = js_DeliverNew;
    }
    natsSubscription* raw = nullptr;
    natsStatus subscribed = NATS_TIMEOUT;
    // A cluster missing a node may place this reader (an ephemeral consumer) on the node
    // that is gone and never answer: another try lands on a live one.
    for (int attempt = 1; attempt <= kSubscribeAttempts && subscribed == NATS_TIMEOUT; ++attempt) {
      subscribed = js_SubscribeSync(&raw, connection.jetstream(), ">", nullptr, &options, nullptr);
      if (subscribed == NATS_TIMEOUT && attempt < kSubscribeAttempts)
        std::fprintf(stderr, "kew-watch: no answer from JetStream to reading %s: trying again\n", flags.stream.c_str());
    }
    kew::nats::check(subscribed, "JetStream stream " + flags.stream);
    const std::unique_ptr<natsSubscription, decltype(&natsSubscription_Destroy)> subscription(raw,
                                                                                           natsSubscription_Destroy);
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    const kew::Severity min_severity = *kew::kSeverityNames.parse(flags.min_severity);
    kew::protocol::AlertStreamReader reader;
    std::set<std::string> shown;   // alerts printed: their End is printed whatever its severity
    std::set<std::string> hidden;  // alerts opened here below the severity asked, not printed so far
    long alerts = 0;
    std::uint64_t latest_token = 0, stale = 0;
    for (;;) {
      natsMsg* message = nullptr;
      const natsStatus s = natsSubscription_NextMsg(&message, subscription.get(), 1000);
      if (s == NATS_TIMEOUT) continue;
      if (s == NATS_SLOW_CONSUMER) {
        // The ordered consumer starts again where the client's backlog overflowed.
        std::fprintf(stderr, "kew-watch: falling behind %s; the client resumes in order\n", flags.stream.c_str());
        continue;
      }
      kew::nats::check(s, "reading " + flags.stream);
      std::string line(natsMsg_GetData(message), static_cast<std::size_t>(natsMsg_GetDataLength(message)));
      const std::uint64_t token = fencing_token(message);
      natsMsg_Destroy(message);
      // Hot standby: a message of an earlier holding than one already read was sent by an
      // instance that had lost the lease (design §5.9): not the pair's.
      if (token && token < latest_token) {
        if (stale++ % 100 == 0)
          std::fprintf(stderr, "kew-watch: %llu messages of an instance that no longer held the lease skipped\n",
                       static_cast<unsigned long long>(stale));
        continue;
      }
      latest_token = std::max(latest_token, token);
      line += '\n';
      if (!reader.read(line)) {
        std::fprintf(stderr, "kew-watch: unreadable message in %s: %s\n", flags.stream.c_str(), reader.error().c_str());
        continue;
      }
      if (reader.object_class() == StreamObjectClass::Alert) {
        if (!passes_filter(reader.alert(), min_severity, shown, hidden)) continue;
      }
      if (show(flags, reader, line, flags.nats_url) == Shown::Alert && flags.count > 0 && ++alerts >= flags.count)
        return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kew-watch: %s\n", e.what());
    return kConnectionFailed;
  }
}

}  // namespace

int main(int argc, char** argv) {
  Flags flags;
  CLI::App app{"kew-watch: follow kewd's conflict alerts"};
  app.set_version_flag("--version", kew::protocol::version_line("kew-watch"));
  app.add_option("address", flags.address, "kewd's alert stream, HOST:PORT")->default_val(flags.address);
  app.add_option("-s,--min-severity", flags.min_severity, kew::kSeverityNames.list({kew::Severity::None}))
      ->check(CLI::IsMember(kew::kSeverityNames.names({kew::Severity::None})))
      ->default_val(flags.min_severity);
  app.add_option("-n,--count", flags.count, "exit after this many ALERT objects")->check(CLI::PositiveNumber);
  app.add_flag("-j,--json", flags.json, "print the stream's JSON lines as received");
  app.add_flag("-a,--alive", flags.alive, "print ALIVE status lines too");
  app.add_flag("-t,--tracks", flags.tracks, "ask for TRACK objects too (printed with --json)");
  auto* nats = app.add_option("--nats", flags.nats_url,
                              "read the alerts kewd publishes on NATS (JetStream) at this URL, nats://HOST:PORT "
                              "(a cluster's servers comma-separated), instead of its stream");
  app.add_option("--stream", flags.stream, "with --nats: the JetStream stream of [nats] stream")
      ->default_val(flags.stream)
      ->needs(nats);
  app.add_option("--since", flags.since,
                 "with --nats: every event kept after this seq (the last one seen), then the new ones")
      ->needs(nats);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }
  if (!flags.nats_url.empty()) return watch_nats(flags);
  std::string error;
  const std::optional<kew::config::HostPort> address = kew::config::parse_host_port(flags.address, &error);
  if (!address) {
    std::fprintf(stderr, "kew-watch: %s\n", error.c_str());
    return kUsageError;
  }

  asio::io_context io;
  tcp::socket socket(io);
  try {
    tcp::resolver resolver(io);
    asio::connect(socket, resolver.resolve(address->host, std::to_string(address->port)));
    const std::string watch = fmt::format("?WATCH={{\"enable\":true,\"min_severity\":\"{}\",\"tracks\":{}}}\n",
                                          flags.min_severity, flags.tracks ? "true" : "false");
    asio::write(socket, asio::buffer(watch));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kew-watch: %s: %s\n", flags.address.c_str(), e.what());
    return kConnectionFailed;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  kew::protocol::AlertStreamReader reader;
  asio::streambuf buffer;
  long alerts = 0;
  for (;;) {
    boost::system::error_code ec;
    const std::size_t n = asio::read_until(socket, buffer, '\n', ec);
    if (ec) {
      if (ec != asio::error::eof) std::fprintf(stderr, "kew-watch: %s\n", ec.message().c_str());
      return ec == asio::error::eof ? 0 : kConnectionFailed;
    }
    std::string line(asio::buffers_begin(buffer.data()), asio::buffers_begin(buffer.data()) + static_cast<long>(n));
    buffer.consume(n);
    if (!reader.read(line)) {
      std::fprintf(stderr, "kew-watch: unreadable line from the server: %s\n", reader.error().c_str());
      continue;
    }
    switch (show(flags, reader, line, flags.address)) {
      case Shown::ServerError: return kConnectionFailed;
      case Shown::Alert:
        if (flags.count > 0 && ++alerts >= flags.count) return 0;
        break;
      case Shown::Other: break;
    }
  }
}
