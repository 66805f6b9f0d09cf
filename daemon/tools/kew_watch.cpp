// kew-watch (design §5.6): a subscriber of kewd's alert stream. Prints one readable line per
// alert event (or the raw JSON lines with --json), like gpsd's cgps/gpspipe.

#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <string>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "kew/config/address.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/protocol/version.hpp"

namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using kew::protocol::StreamObjectClass;

constexpr int kUsageError = 64;
constexpr int kConnectionFailed = 1;
constexpr double kMetresPerNm = 1852.0;

struct Flags {
  std::string address = "127.0.0.1:4747";
  std::string min_severity = "caution";
  long count = 0;  // 0: until the server closes
  bool json = false;
  bool alive = false;
  bool tracks = false;
};

std::string utc(double t) {
  if (!std::isfinite(t)) return "--:--:--";
  const std::time_t seconds = static_cast<std::time_t>(std::floor(t));
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  return fmt::format("{:02}:{:02}:{:02}Z", tm.tm_hour, tm.tm_min, tm.tm_sec);
}

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

void print_alert(const kew::AlertEvent& e, const char* state) {
  std::string line = fmt::format("{} {:<6} {:<7} {} x {}", utc(e.t), state, kew::to_string(e.severity), party(e.a),
                                 party(e.b));
  if (e.state != kew::AlertState::End) {
    line += fmt::format("  t_los {:>3.0f} s  cpa {:.1f} NM {:.0f} ft in {:.0f} s", e.t_los_s, e.cpa_h_m / kMetresPerNm,
                        e.cpa_v_ft, e.t_cpa_s);
    line += fmt::format("  by {}", kew::to_string(e.hypothesis));
  }
  if (!e.region.empty()) line += fmt::format("  region {}", e.region);
  if (e.acknowledged) line += "  ack";
  std::printf("%s  [%s]\n", line.c_str(), e.id.c_str());
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }
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
    const StreamObjectClass kind = reader.object_class();
    if (flags.json) {
      std::fputs(line.c_str(), stdout);
    } else if (kind == StreamObjectClass::Version) {
      std::printf("connected to kewd %s (%s, protocol %d) at %s\n", reader.text().c_str(),
                  reader.revision().empty() ? "revision unknown" : reader.revision().c_str(), reader.proto(),
                  flags.address.c_str());
    } else if (kind == StreamObjectClass::Start) {
      // kewd (re)started: a new run id; alerts open before it ended with reason "restart".
      std::printf("START  kewd %s run %s started %s\n", reader.text().c_str(), reader.run().c_str(),
                  utc(reader.start_t()).c_str());
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
                  a.last_data_t ? utc(*a.last_data_t).c_str() : "--:--:--", static_cast<unsigned long long>(a.tracks),
                  static_cast<unsigned long long>(a.alerts), a.records_per_s, health.c_str());
    }
    if (kind == StreamObjectClass::Error) {
      std::fprintf(stderr, "kew-watch: server error: %s\n", reader.text().c_str());
      return kConnectionFailed;
    }
    if (kind == StreamObjectClass::Alert && flags.count > 0 && ++alerts >= flags.count) return 0;
  }
}
