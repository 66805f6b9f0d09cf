// readsb-style JSON lines (recordings/adsb_actions-readsb); the format is described in
// readsb.hpp.
#include "readsb_members.hpp"
#include "kew/protocol/readsb.hpp"
#include "line_decoder.hpp"

namespace kew::protocol {
namespace {

using text::LineResult;

class ReadsbDecoder final : public text::LineDecoder {
 public:
  explicit ReadsbDecoder(const ReadsbOptions& options)
      : LineDecoder(options.max_line_bytes), json_(max_message_bytes()) {}

  std::string_view format_name() const override { return "readsb"; }

 private:
  LineResult decode_line(std::string_view line, const ReportSink& sink) override {
    text::ReadsbMembers top;
    text::ReadsbMembers nested;
    LineResult result = json_.parse(line, [&](std::string_view key, auto& value) -> LineResult {
      if (key == "flightdict") return text::read_flightdict(value, nested);
      return text::read_readsb_member(key, value, top);
    });
    if (result) return result;
    top.complete_from(nested);
    if (!top.lat || !top.lon) return text::problem("no_position", "no lat/lon");
    if (!top.now) return text::problem("missing_field", "no \"now\"");
    if (!top.hex) return text::problem("missing_field", "no \"hex\"");
    if (LineResult bad = text::fill_readsb_report(top, *top.now, "readsb", report_)) return bad;
    if (LineResult bad = text::check_report(report_)) return bad;
    sink(report_);
    return std::nullopt;
  }

  text::JsonObjectParser json_;
  TrackReport report_;
};

}  // namespace

std::unique_ptr<Decoder> make_readsb_decoder(const ReadsbOptions& options) {
  return std::make_unique<ReadsbDecoder>(options);
}

}  // namespace kew::protocol
