#include "kew/zone/zone.hpp"

#include "kew/geometry/hilbert.hpp"
#include "kew/util/gentle_growth.hpp"

namespace kew::zone {

Zone::Zone(ZoneKey key, std::string name, const geo::Projection& projection, const kinetic::KineticConfig& config,
           double engine_now)
    : key_(key), name_(std::move(name)), projection_(projection), config_(config), engine_(std::in_place, config, engine_now) {}

kinetic::PointId Zone::place(TrackSlot slot, kinetic::PointId point, double engine_t, const probe::Kinematics& now_k) {
  if (point == kinetic::kNoPoint) {
    point = engine_->insert(engine_t, now_k.position, now_k.velocity);
    util::grow_to(slot_of_point_, point + 1, kNoSlot);
    util::grow_to(states_, point + 1);
    slot_of_point_[point] = slot;
  } else {
    engine_->update(point, engine_t, now_k.position, now_k.velocity);
  }
  speeds_.set(point, geometry::norm(now_k.velocity));
  ++statistics_.updates;
  return point;
}

void Zone::remove(kinetic::PointId point, double engine_t) {
  engine_->remove(point, engine_t);
  slot_of_point_[point] = kNoSlot;
  speeds_.erase(point);
}

void Zone::renumber_points(double engine_t, const std::vector<TrackSlot>& slots,
                           const std::vector<probe::Kinematics>& now, std::vector<kinetic::PointId>& new_points) {
  std::vector<geometry::Point2> positions;
  positions.reserve(now.size());
  for (const probe::Kinematics& k : now) positions.push_back(k.position);
  // The old point of each member, in slot_of_point_ order (as `slots` was collected).
  std::vector<kinetic::PointId> old_points;
  for (kinetic::PointId p = 0; p < slot_of_point_.size(); ++p)
    if (slot_of_point_[p] != kNoSlot) old_points.push_back(p);
  const kinetic::KineticStatistics earlier = engine_->statistics();
  std::vector<ProbeState> old_states = std::move(states_);
  states_.clear();
  slot_of_point_.clear();
  speeds_ = {};
  engine_.emplace(config_, engine_t);
  new_points.assign(slots.size(), kinetic::kNoPoint);
  for (const std::uint32_t i : geometry::hilbert_order(positions)) {
    const kinetic::PointId point = engine_->insert(engine_t, now[i].position, now[i].velocity);
    util::grow_to(slot_of_point_, point + 1, kNoSlot);
    util::grow_to(states_, point + 1);
    slot_of_point_[point] = slots[i];
    states_[point] = old_states[old_points[i]];
    speeds_.set(point, geometry::norm(now[i].velocity));
    new_points[i] = point;
  }
  engine_->continue_statistics(earlier);
}

}  // namespace kew::zone
