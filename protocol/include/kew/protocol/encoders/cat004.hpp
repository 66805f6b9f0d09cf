#pragma once
// ASTERIX Category 004, Safety Net Messages (EUROCONTROL ASTERIX Part 17, edition 1.12,
// the edition Wireshark 4.0 decodes), as kew sends it over UDP (design §5.4):
//   Alive (I004/000 = 1); STCA (= 7) or Area Proximity Warning (APW, = 5), by the
//   alert's kind, for new and updated alerts; End Of Conflict (= 17) for the end of either.
// docs/protocol.md lists every item and subfield written, with its scaling and
// the kew value it carries.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "kew/alert/alert_event.hpp"
#include "kew/util/rejections.hpp"

namespace kew::protocol {

/// SAC/SIC pair (I004/010, I004/015).
struct Cat004SourceId {
  std::uint8_t sac = 0;
  std::uint8_t sic = 0;
};

struct Cat004Options {
  /// I004/010: the safety-net server's System Area Code and System Identification Code.
  std::uint8_t sac = 0;
  std::uint8_t sic = 0;
  /// I004/015: the surveillance data processing system the tracks come from, when the
  /// configuration names one; absent: the item is not sent.
  std::optional<Cat004SourceId> sdps;
  /// Largest datagram produced, bytes, in [kCat004MinDatagramBytes, 65535] (clamped).
  /// The default fits one Ethernet frame (1500 − 20 IPv4 − 8 UDP).
  std::size_t max_datagram_bytes = 1472;
};

/// Smallest max_datagram_bytes honoured: always room for the largest record kew writes.
inline constexpr std::size_t kCat004MinDatagramBytes = 256;

enum class Cat004MessageType : std::uint8_t {
  Alive = 1,
  Apw = 5,
  Stca = 7,
  EndOfConflict = 17,
};

/// What an Alive message says (I004/060 Safety Net Function and System Status).
struct Cat004Alive {
  /// Time of the message, UTC seconds since the Unix epoch (only the time of day is sent).
  double t = 0.0;
  /// DG: information from one or more inputs is lost (feed stale).
  bool degraded = false;
  /// OF: more alerts than the service handles safely (alerts may be dropped).
  bool overflow = false;
  /// OL: the service cannot keep up; correct calculation is not guaranteed.
  bool overload = false;
  /// APW: the area proximity warning runs (volumes are watched). STCA always runs.
  bool apw = false;
};

/// Builds CAT004 datagrams: records are packed into one data block per datagram, in the
/// order added, a new datagram starting when the next record would not fit.
class Cat004Encoder {
 public:
  explicit Cat004Encoder(Cat004Options options);

  /// Adds an Alive message. Returns false (counted as "cat004_bad_time") when `alive.t`
  /// is not finite.
  bool add_alive(const Cat004Alive& alive);

  /// Adds an STCA message (kind Stca, state New or Update), an APW message (kind Apw,
  /// New or Update: aircraft `a` and the volume's name, no second aircraft) or an End
  /// Of Conflict message (End, either kind). Returns false (counted as
  /// "cat004_bad_time") when `event.t` is not finite; figures that are not finite are
  /// left out of the message, figures out of an item's range are saturated (see
  /// docs/protocol.md).
  bool add_alert(const AlertEvent& event);

  /// True when no record was added since the last take_datagrams().
  bool empty() const { return datagrams_.empty(); }

  /// Hands over every datagram built so far (each one complete CAT004 data block) and
  /// starts afresh.
  std::vector<std::vector<std::byte>> take_datagrams();

  const Rejections& rejections() const { return rejections_; }
  const Cat004Options& options() const { return options_; }

 private:
  /// Appends one encoded record to the open datagram, or to a new one when it is full.
  void append_record(std::span<const std::byte> record);

  Cat004Options options_;
  std::vector<std::vector<std::byte>> datagrams_;
  Rejections rejections_;
};

/// Time of day carried by I004/020 and kin: seconds since the last UTC midnight of `t`
/// (UTC seconds since the epoch, finite), in [0, 86400).
double cat004_time_of_day(double t);

}  // namespace kew::protocol
