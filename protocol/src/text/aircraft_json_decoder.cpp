// aircraft.json snapshots; the format is described in aircraft_json.hpp.
#include <algorithm>
#include <limits>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "json_object_cutter.hpp"
#include "kew/protocol/aircraft_json.hpp"
#include "readsb_members.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// Above this "now" is taken as milliseconds (as opensky-json's timestamps).
constexpr double kMillisecondTimeAbove = 1e11;

class AircraftJsonDecoder final : public Decoder {
 public:
  explicit AircraftJsonDecoder(const AircraftJsonOptions& options)
      : options_(options),
        max_bytes_(std::max<std::size_t>(options.max_snapshot_bytes, 64)),
        cutter_("aircraft.json snapshot", max_bytes_),
        json_(0) {}

  std::string_view format_name() const override { return "aircraft-json"; }
  std::size_t max_message_bytes() const override { return max_bytes_; }

  void feed(std::span<const std::byte> bytes, const ReportSink& sink) override {
    cutter_.feed(
        bytes, [&](std::string_view snapshot) { decode_snapshot(snapshot, sink); },
        [&](std::string_view reason, std::string message) { rejections().reject(reason, message); });
  }

  // The end of the stream: the decoder is as new (a stream read again reports again).
  void finish(const ReportSink& sink) override {
    end_message(sink);
    last_reported_.clear();
    newest_now_ = -std::numeric_limits<double>::infinity();
  }
  // A datagram (a NATS message, a snapshot fetched) ends its framing, but the snapshots go
  // on: what was reported stays known, so the next one reports only what is new.
  void end_message(const ReportSink& /*sink*/) override {
    const std::uint64_t snapshot = cutter_.object_number();
    if (cutter_.finish())
      rejections().reject("truncated", fmt::format("aircraft.json snapshot {}: cut by the end of the stream", snapshot));
  }

 private:
  void refuse(std::string_view where, const text::LineProblem& problem) {
    rejections().reject(problem.reason, fmt::format("{}: {}: {}", where, problem.reason, problem.detail));
  }

  void decode_snapshot(std::string_view text, const ReportSink& sink) {
    const std::string where = fmt::format("aircraft.json snapshot {}", cutter_.object_number());
    std::optional<double> now;
    std::optional<simdjson::dom::element> aircraft;
    LineResult bad = json_.parse(text, [&](std::string_view key, simdjson::dom::element value) -> LineResult {
      if (key == "now") return text::read_number(value, key, now);
      if (key == "aircraft" || key == "ac") aircraft = value;
      return std::nullopt;
    });
    if (!bad && !now) bad = text::problem("missing_field", "no \"now\"");
    if (!bad && !aircraft) bad = text::problem("missing_field", "no \"aircraft\" or \"ac\"");
    simdjson::dom::array list;
    if (!bad && aircraft->get_array().get(list) != simdjson::SUCCESS)
      bad = text::problem("wrong_type", "\"aircraft\" is not an array");
    if (bad) {
      refuse(where, *bad);
      return;
    }
    const double t_now = *now > kMillisecondTimeAbove ? *now / 1000.0 : *now;
    ready_.clear();
    std::size_t index = 0;
    for (const simdjson::dom::element entry : list) {
      ++index;
      if (const LineResult problem = decode_aircraft(entry, t_now))
        refuse(fmt::format("{} aircraft {}", where, index), *problem);
    }
    std::stable_sort(ready_.begin(), ready_.end(),
                     [](const TrackReport& a, const TrackReport& b) { return a.t < b.t; });
    for (const TrackReport& report : ready_) sink(report);
    // A snapshot older than one read before (a history read out of order) forgets nothing.
    newest_now_ = std::max(newest_now_, t_now);
    forget_older_than(newest_now_ - options_.max_position_age_s);
  }

  LineResult decode_aircraft(simdjson::dom::element entry, double now) {
    simdjson::dom::object object;
    if (entry.get_object().get(object) != simdjson::SUCCESS) return text::problem("bad_json", "not a JSON object");
    text::ReadsbMembers m;
    for (const simdjson::dom::key_value_pair member : object)
      if (LineResult r = text::read_readsb_member(member.key, member.value, m)) return r;
    if (!m.hex) return text::problem("missing_field", "no \"hex\"");
    if (!m.lat || !m.lon) return std::nullopt;  // no position: nothing to report
    const double age = m.seen_pos ? *m.seen_pos : m.seen.value_or(0.0);
    if (!(age >= 0.0) || age > options_.max_position_age_s) return std::nullopt;
    TrackReport report;
    if (LineResult bad = text::fill_readsb_report(m, now - age, "aircraft-json", report)) return bad;
    // The same position in a later snapshot (its age grown by the time between them).
    std::uint32_t key = 0;
    std::string id;
    text::parse_address(*m.hex, id, key);
    const auto reported = last_reported_.find(key);
    if (reported != last_reported_.end() && report.t <= reported->second + kSamePosition_s) return std::nullopt;
    if (LineResult bad = text::check_report(report)) return bad;
    last_reported_[key] = report.t;
    ready_.push_back(std::move(report));
    return std::nullopt;
  }

  /// Every position reported before `t` is older than any a later snapshot may report.
  void forget_older_than(double t) { std::erase_if(last_reported_, [t](const auto& e) { return e.second < t; }); }

  // now − seen_pos of one position in two snapshots differs by their rounding (readsb
  // writes seen_pos to 0.1 s, now to 0.1 s or 1 ms): within this it is the same one.
  static constexpr double kSamePosition_s = 0.15;

  AircraftJsonOptions options_;
  std::size_t max_bytes_;
  text::JsonObjectCutter cutter_;
  text::JsonObjectParser json_;
  std::unordered_map<std::uint32_t, double> last_reported_;  // address key → data time reported
  std::vector<TrackReport> ready_;
  double newest_now_ = -std::numeric_limits<double>::infinity();
};

}  // namespace

std::unique_ptr<Decoder> make_aircraft_json_decoder(const AircraftJsonOptions& options) {
  return std::make_unique<AircraftJsonDecoder>(options);
}

}  // namespace kew::protocol
