#include "kew/zone/zone.hpp"

#include "kew/geometry/hilbert.hpp"
#include "kew/util/gentle_growth.hpp"

namespace kew::zone {

Zone::Zone(ZoneKey key, std::string name, const geo::Projection& projection, const kinetic::KineticConfig& config,
           double engine_now)
    : key_(key), name_(std::move(name)), projection_(projection), config_(config), engine_(std::in_place, config, engine_now) {}

kinetic::PointId Zone::place(TrackSlot slot, double engine_t, const probe::Kinematics& now_k) {
  const auto [it, inserted] = point_of_slot_.try_emplace(slot, kinetic::kNoPoint);
  if (inserted) {
    it->second = engine_->insert(engine_t, now_k.position, now_k.velocity);
    util::grow_to(slot_of_point_, it->second + 1, kNoSlot);
    util::grow_to(states_, it->second + 1);
    slot_of_point_[it->second] = slot;
  } else {
    engine_->update(it->second, engine_t, now_k.position, now_k.velocity);
  }
  speeds_.set(it->second, geometry::norm(now_k.velocity));
  ++statistics_.updates;
  return it->second;
}

void Zone::remove(TrackSlot slot, double engine_t) {
  const auto it = point_of_slot_.find(slot);
  if (it == point_of_slot_.end()) return;
  engine_->remove(it->second, engine_t);
  slot_of_point_[it->second] = kNoSlot;
  speeds_.erase(it->second);
  point_of_slot_.erase(it);
}

void Zone::renumber(double engine_t, double at) {
  std::vector<kinetic::PointId> old_points;
  std::vector<probe::Kinematics> now;
  std::vector<geometry::Point2> positions;
  for (kinetic::PointId p = 0; p < slot_of_point_.size(); ++p) {
    if (slot_of_point_[p] == kNoSlot) continue;
    old_points.push_back(p);
    // The last report extrapolated: the position and velocity place() was given.
    now.push_back(probe::extrapolated(states_[p].kinematics, at - states_[p].t));
    positions.push_back(now.back().position);
  }
  const kinetic::KineticStatistics earlier = engine_->statistics();
  std::vector<ProbeState> old_states = std::move(states_);
  std::vector<TrackSlot> old_slots = std::move(slot_of_point_);
  states_.clear();
  slot_of_point_.clear();
  speeds_ = {};
  engine_.emplace(config_, engine_t);
  for (const std::uint32_t i : geometry::hilbert_order(positions)) {
    const kinetic::PointId point = engine_->insert(engine_t, now[i].position, now[i].velocity);
    util::grow_to(slot_of_point_, point + 1, kNoSlot);
    util::grow_to(states_, point + 1);
    const TrackSlot slot = old_slots[old_points[i]];
    slot_of_point_[point] = slot;
    states_[point] = old_states[old_points[i]];
    speeds_.set(point, geometry::norm(now[i].velocity));
    point_of_slot_[slot] = point;
  }
  engine_->continue_statistics(earlier);
}

}  // namespace kew::zone
