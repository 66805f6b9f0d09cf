#include "kew/alert/alert_event.hpp"

namespace kew {

std::string_view to_string(Severity s) {
  switch (s) {
    case Severity::Loss: return "loss";
    case Severity::Warning: return "warning";
    case Severity::Caution: return "caution";
    case Severity::None: break;
  }
  return "none";
}

std::string_view to_string(AlertState s) {
  switch (s) {
    case AlertState::New: return "new";
    case AlertState::Update: return "update";
    case AlertState::End: break;
  }
  return "end";
}

std::string_view to_string(AlertEndReason r) {
  switch (r) {
    case AlertEndReason::Cleared: return "cleared";
    case AlertEndReason::TrackDropped: return "track_dropped";
    case AlertEndReason::None: break;
  }
  return "";
}

bool parse_severity(std::string_view text, Severity& out) {
  for (Severity s : {Severity::None, Severity::Caution, Severity::Warning, Severity::Loss}) {
    if (text == to_string(s)) {
      out = s;
      return true;
    }
  }
  return false;
}

}  // namespace kew
