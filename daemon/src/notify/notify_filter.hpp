#pragma once
// Which alert events a notifier sends, and what each is to it (design §5.10): new,
// escalated (its severity rose above any it had, or first reached min_severity), updated
// or ended; filtered by severity, state, kind, region and the parties' callsigns or
// addresses or the volume's name.

#include <optional>
#include <string>
#include <unordered_map>

#include "kew/alert/alert_event.hpp"
#include "kew/daemon/notify_config.hpp"

namespace kew::daemon {

class NotifyFilter {
 public:
  explicit NotifyFilter(const NotifyConfig& config);

  /// What `event` is to this notifier, or nullopt when it is not sent. Called with every
  /// alert event in seq order (filtered or not), so that it follows each alert's severity.
  std::optional<NotifyState> classify(const AlertEvent& event);

 private:
  /// The kind, region, party and volume filters.
  bool concerns(const AlertEvent& event) const;
  bool passes(NotifyState state) const;

  struct Followed {
    Severity highest = Severity::None;
    bool reached = false;    ///< an event of it passed min_severity and the party filters
    bool announced = false;  ///< a message about it was sent (or is waiting)
  };
  const NotifyConfig& config_;
  std::unordered_map<std::string, Followed> alerts_;
};

}  // namespace kew::daemon
