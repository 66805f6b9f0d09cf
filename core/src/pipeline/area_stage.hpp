#pragma once
// The area proximity warning (design §4.11), the alert stage's second safety net: each
// judged track's predicted path against the volumes within its reach, through the alert
// manager the pairs use, so that both kinds share confirmation, clearing, numbers and
// sequence. Fixed volumes are found in an R-tree; a volume that follows an aircraft is a
// circle around that track, judged as a pair with the circle's radius and band.

#include <cstdint>
#include <optional>
#include <vector>

#include "batch.hpp"
#include "kew/alert/alert_manager.hpp"
#include "kew/eligibility/eligibility.hpp"
#include "kew/util/checkpoint_io.hpp"
#include "kew/util/rejections.hpp"
#include "kew/volume/volume_index.hpp"
#include "kew/volume/watched_volume.hpp"
#include "zone_set.hpp"

namespace kew::pipeline {

class AreaStage {
 public:
  /// `volumes`: the configuration's, indexed by their position (the alert manager's
  /// volume numbers, < 2^31); every argument must outlive the stage.
  AreaStage(const std::vector<volume::WatchedVolume>& volumes, const eligibility::Rules& rules, ZoneSet& zones);

  bool empty() const { return volumes_.empty(); }

  /// Judges the track in `slot`, as `view` holds it, at data time `now` (UTC s ≥ its
  /// record's): every volume its path over the look-ahead can enter, every volume
  /// following another aircraft near it, and every volume it has an alert or a pending
  /// one about. Events go to `out`, in volume order; rules that turned an entry clear
  /// are counted in `suppressed`.
  void judge(track::TrackSlot slot, const std::vector<Snapshot>& view, double now, alert::AlertManager& alerts,
             Rejections& suppressed, std::vector<AlertEvent>& out);
  /// The track in `slot` left the probe: a volume that followed it goes with it, and so
  /// do the alerts about that volume.
  void track_left(track::TrackSlot slot, double now, alert::AlertManager& alerts, std::vector<AlertEvent>& out);

  /// The stage's state (which track each followed volume is centred on).
  void save(util::CheckpointWriter& out) const;
  void restore(util::CheckpointReader& in);

 private:
  /// Where a path stands against one volume.
  struct Approach {
    bool enters = false;      ///< inside within the look-ahead
    bool inside_now = false;  ///< inside at `now`
    double t_entry_s = 0.0;   ///< from now (0 when inside)
    bool level_off = false;   ///< found with a levelling-off vertical prediction
  };
  Approach fixed_approach(const volume::WatchedVolume& v, const Snapshot& s, double now) const;
  /// nullopt when the followed aircraft is unknown, is the track itself, or is too far.
  std::optional<Approach> followed_approach(std::uint32_t v, track::TrackSlot slot, const std::vector<Snapshot>& view,
                                            double now);
  void follow(track::TrackSlot slot, const track::Track& t);

  const std::vector<volume::WatchedVolume>& volumes_;
  const eligibility::Rules& rules_;
  ZoneSet& zones_;
  std::vector<std::uint32_t> fixed_;     // the index's positions → volume numbers
  std::vector<std::uint32_t> followers_; // volume numbers of the volumes that follow
  std::vector<track::TrackSlot> centre_; // by volume number: the followed track, or kNoTrack
  volume::VolumeIndex index_;
  double longest_lookahead_s_ = 0.0;
  /// A fixed volume's band (ft), kept apart from the volumes for the candidates' first
  /// test; by volume number.
  struct Band {
    double floor_ft = 0.0, ceiling_ft = 0.0;
    bool fixed = false;  ///< a fixed volume's (a followed one's band moves)
  };
  std::vector<Band> bands_;
  std::vector<std::uint32_t> judged_;  // scratch: the volumes of one judgement
  std::vector<std::uint32_t> held_;    // scratch: those with an alert or a pending one, sorted
};

}  // namespace kew::pipeline
