// aircraft.json snapshots; the format is described in aircraft_json.hpp.
#include "kew/protocol/aircraft_json.hpp"
#include "readsb_members.hpp"
#include "snapshot_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

// Above this "now" is taken as milliseconds (as opensky-json's timestamps).
constexpr double kMillisecondTimeAbove = 1e11;
// now − seen_pos of one position in two snapshots differs by their rounding (readsb
// writes seen_pos to 0.1 s, now to 0.1 s or 1 ms): within this it is the same one.
constexpr double kSamePosition_s = 0.15;

class AircraftJsonDecoder final : public text::SnapshotDecoder {
 public:
  explicit AircraftJsonDecoder(const AircraftJsonOptions& options)
      : SnapshotDecoder("aircraft.json snapshot", options.max_snapshot_bytes,
                        {.same_position_s = kSamePosition_s, .forget_after_s = options.max_position_age_s}),
        max_position_age_s_(options.max_position_age_s) {}

  std::string_view format_name() const override { return "aircraft-json"; }

 private:
  std::optional<double> decode_snapshot(std::string_view text, const std::string& where) override {
    std::optional<double> now;
    std::optional<simdjson::dom::element> aircraft;
    LineResult bad = json().parse(text, [&](std::string_view key, simdjson::dom::element value) -> LineResult {
      if (key == "now") return text::read_number(value, key, now);
      if (key == "aircraft" || key == "ac") aircraft = value;
      return std::nullopt;
    });
    if (!bad && !now) bad = text::problem("missing_field", "no \"now\"");
    const double t_now = now && *now > kMillisecondTimeAbove ? *now / 1000.0 : now.value_or(0.0);
    if (!bad)
      bad = decode_entries(aircraft, "\"aircraft\" (or \"ac\")", where, "aircraft",
                           [&](simdjson::dom::element entry) { return decode_aircraft(entry, t_now); });
    if (bad) {
      refuse(where, *bad);
      return std::nullopt;
    }
    return t_now;
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
    if (!(age >= 0.0) || age > max_position_age_s_) return std::nullopt;
    TrackReport report;
    if (LineResult bad = text::fill_readsb_report(m, now - age, "aircraft-json", report)) return bad;
    return offer(report);
  }

  double max_position_age_s_;
};

}  // namespace

std::unique_ptr<Decoder> make_aircraft_json_decoder(const AircraftJsonOptions& options) {
  return std::make_unique<AircraftJsonDecoder>(options);
}

}  // namespace kew::protocol
