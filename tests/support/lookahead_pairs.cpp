#include "lookahead_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kew::testing {

using geometry::Point2;
using geometry::Vector2;
using kinetic::kNoPoint;

namespace {

kinetic::KineticConfig q_triangulation(kinetic::KineticConfig config) {
  config.tolerance = 0.0;  // every model change moves the q-point: LookaheadPairs decides when
  config.tolerance_mode = kinetic::ToleranceMode::Absolute;
  config.keep_model_s = 0.0;
  return config;
}

}  // namespace

LookaheadPairs::LookaheadPairs(const LookaheadPairsConfig& config, double start_time)
    : config_(config),
      // 1 m over S + 2ε absorbs the rounding of event times and of the q-points.
      widened_(config.separation_m + 2.0 * config.tolerance_m + 1.0),
      kdt_(q_triangulation(config.kinetic), start_time),
      near_end_(static_cast<double>(bucket_of(start_time) + 1) * kBucket_s) {
  kdt_.set_edge_listener(this);
}

// ---------------------------------------------------------------------------------
// Models and membership

Point2 LookaheadPairs::model_position(PointId id) const {
  return kdt_.position_now(id) - config_.lookahead_s * kdt_.velocity(id);
}

LookaheadPairs::Interval LookaheadPairs::membership(PointId a, PointId b) const {
  constexpr Interval kEmpty{0.0, 0.0};
  const double now = kdt_.now();
  const Vector2 d = model_position(b) - model_position(a);
  const Vector2 w = kdt_.velocity(b) - kdt_.velocity(a);
  const double ww = geometry::dot(w, w);
  const double c = geometry::dot(d, d) - widened_ * widened_;
  // |d + w·u| < S' for u in (u1, u2); H holds the pair while [t, t + T] meets it.
  if (ww == 0.0) return c < 0.0 ? Interval{-kinetic::kNever, kinetic::kNever} : kEmpty;
  const double h = geometry::dot(d, w);
  const double disc = h * h - ww * c;
  if (!(disc > 0.0)) return kEmpty;
  const double root = std::sqrt(disc);
  const double far = h >= 0.0 ? -(h + root) : -(h - root);  // no cancellation
  double u1 = far / ww, u2 = far != 0.0 ? c / far : -u1;
  if (u1 > u2) std::swap(u1, u2);
  return {now + u1 - config_.lookahead_s, now + u2};
}

bool LookaheadPairs::holds(PointId a, PointId b) const {
  const auto& pa = partners_[a];
  const auto& pb = partners_[b];
  const auto& shorter = pa.size() <= pb.size() ? pa : pb;
  const PointId other = pa.size() <= pb.size() ? b : a;
  return std::any_of(shorter.begin(), shorter.end(), [other](const Partner& p) { return p.id == other; });
}

std::size_t LookaheadPairs::pair_ends() const {
  std::size_t n = 0;
  for (const auto& p : partners_) n += p.size();
  return n;
}

// ---------------------------------------------------------------------------------
// H

void LookaheadPairs::push(double time, Kind kind, PointId a, PointId b) {
  const Event e{time, next_seq_++, a, b, version_[a], kind == Kind::Drift ? 0u : version_[b], kind};
  if (time < near_end_) {
    queue_.push(e);
  } else {
    far_[bucket_of(time)].push_back(e);
    ++far_size_;
  }
  stats_.queue_max = std::max(stats_.queue_max, queue_.size() + far_size_);
}

void LookaheadPairs::consider(PointId a, PointId b, double at, double before) {
  if (a == b) return;
  ++stats_.two_hop_considered;
  // The interval first: it rules most candidates out without reading H.
  const Interval in = membership(a, b);
  if (!(in.end > at)) return;
  if (in.begin > at && !(in.begin < before)) {
    ++stats_.two_hop_pruned;
    return;
  }
  if (holds(a, b)) return;
  if (in.begin <= at) {
    work_.push_back({a, b, in.end});
  } else {
    ++stats_.entries_queued;
    push(in.begin, Kind::Entry, a, b);
  }
}

bool LookaheadPairs::add_pair(PointId a, PointId b, double exit) {
  if (holds(a, b)) return false;
  ++stats_.entries;
  partners_[a].push_back({b, exit});
  partners_[b].push_back({a, exit});
  if (exit < kinetic::kNever) push(exit, Kind::Exit, a, b);
  return true;
}

void LookaheadPairs::enter(PointId a, PointId b, double at) {
  work_.push_back({a, b, membership(a, b).end});
  enter_waiting(at);
}

void LookaheadPairs::enter_waiting(double at) {
  while (!work_.empty()) {
    const auto [x, y, exit] = work_.back();
    work_.pop_back();
    if (!add_pair(x, y, exit)) continue;
    // The Gabriel gap: a pair (k, y) with k a partner of x may enter while both halves
    // are in H, without ever being a q-edge; x is its witness only until a half leaves.
    // (Indexed loops: consider() does not touch partners_, but stay safe on reallocation.)
    for (std::size_t n = 0; n < partners_[x].size(); ++n) {
      const Partner k = partners_[x][n];
      consider(k.id, y, at, std::min(exit, k.exit));
    }
    for (std::size_t n = 0; n < partners_[y].size(); ++n) {
      const Partner k = partners_[y][n];
      consider(k.id, x, at, std::min(exit, k.exit));
    }
  }
}

void LookaheadPairs::edge_solved(PointId a, PointId b) {
  ++stats_.edges_told;
  // A point being inserted is not live yet: report() considers its edges afterwards.
  if (!live(a) || !live(b) || holds(a, b)) return;
  const double now = kdt_.now();
  consider(a, b, now);
  // The point whose model is being replaced: its current pairs come from find_pairs(),
  // only the future entries of its new edges are kept from here.
  if (a == replacing_ || b == replacing_) work_.clear();
  enter_waiting(now);
}

void LookaheadPairs::drop_partner(PointId from, PointId partner) {
  auto& mine = partners_[from];
  const auto at = std::find_if(mine.begin(), mine.end(), [partner](const Partner& p) { return p.id == partner; });
  *at = mine.back();
  mine.pop_back();
}

void LookaheadPairs::forget_pairs(PointId id) {
  for (const Partner& k : partners_[id]) drop_partner(k.id, id);
  partners_[id].clear();
}

void LookaheadPairs::search_disk(PointId id) {
  ++stats_.disk_searches;
  found_.clear();
  // Any j with a model pair in H now lies within S' + v_max·T of p_i in the q-plane:
  // |q_j − p_i| ≤ |p_j + v_j·s − p_i − v_i·s| + |v_j|·(T − s) + |v_i|·s < S' + v_max·T.
  search_.within_around(kdt_, id, model_position(id),
                        widened_ + config_.max_speed_mps * config_.lookahead_s + 1.0, found_);
}

void LookaheadPairs::find_pairs(PointId id) {
  forget_pairs(id);
  search_disk(id);
  const double now = kdt_.now();
  for (const PointId j : found_) consider(id, j, now);
  // Its current pairs (all waiting pairs hold id) go in without their closures first ...
  for (const Waiting& w : work_) add_pair(w.a, w.b, w.exit);
  work_.clear();
  // ... then the two hops at once: pairs of its partners, with id the witness, each pair
  // once; and pairs of id with the partners' partners, each point once (a point reached
  // through several partners would otherwise be computed once per partner).
  const std::vector<Partner>& mine = partners_[id];
  for (std::size_t m = 0; m < mine.size(); ++m)
    for (std::size_t n = 0; n < m; ++n) consider(mine[m].id, mine[n].id, now, std::min(mine[m].exit, mine[n].exit));
  ++mark_round_;
  if (mark_.size() < key_of_.size()) mark_.resize(key_of_.size(), 0);
  mark_[id] = mark_round_;
  for (const Partner& j : mine) mark_[j.id] = mark_round_;
  for (const Partner& j : mine)
    for (const Partner& k : partners_[j.id])
      if (mark_[k.id] != mark_round_) {
        mark_[k.id] = mark_round_;
        consider(k.id, id, now);
      }
  enter_waiting(now);
}

void LookaheadPairs::replace_model(PointId id, Point2 p, Vector2 v) {
  version_[id] += 2;  // stays odd: live
  drift_seq_[id] = 0;
  forget_pairs(id);
  const bool hosted = !kdt_.twins_of(id).empty();
  replacing_ = id;
  kdt_.update(id, kdt_.now(), p + config_.lookahead_s * v, v);
  replacing_ = kNoPoint;
  if (hosted) twin_changes_seen_ = ~std::uint64_t{0};  // its twins were reattached: look
  sync_twins();
  if (!is_twin_[id]) find_pairs(id);
}

void LookaheadPairs::sync_twins() {
  const kinetic::KineticStatistics& s = kdt_.statistics();
  const std::uint64_t changes = s.twins_created + s.twins_released + s.repair_reinsertions + s.rebuilds;
  if (changes == twin_changes_seen_) return;
  twin_changes_seen_ = changes;
  twins_.clear();
  std::vector<PointId> released;
  for (PointId id = 0; id < key_of_.size(); ++id) {
    if (!live(id)) continue;
    const bool twin = kdt_.host_of(id) != id;
    if (twin) twins_.push_back(id);
    else if (is_twin_[id]) released.push_back(id);
    is_twin_[id] = twin ? 1 : 0;
  }
  for (const PointId id : released) find_pairs(id);
}

// ---------------------------------------------------------------------------------
// Time and reports

void LookaheadPairs::run_event(const Event& e) {
  if (!current(e)) {
    ++stats_.events_stale;
    return;
  }
  switch (e.kind) {
    case Kind::Entry:
      if (holds(e.a, e.b)) ++stats_.events_stale;
      else enter(e.a, e.b, e.time);
      return;
    case Kind::Exit: {
      if (!holds(e.a, e.b)) return;
      ++stats_.exits;
      drop_partner(e.a, e.b);
      drop_partner(e.b, e.a);
      return;
    }
    case Kind::Drift: {
      if (drift_seq_[e.a] != e.seq) {
        ++stats_.events_stale;
        return;
      }
      ++stats_.drifts;
      const Report& r = pending_[e.a];
      replace_model(e.a, r.p + (e.time - r.t) * r.v, r.v);
      return;
    }
  }
}

bool LookaheadPairs::current(const Event& e) const {
  return version_[e.a] == e.version_a && (e.kind == Kind::Drift || version_[e.b] == e.version_b);
}

std::int64_t LookaheadPairs::bucket_of(double time) { return static_cast<std::int64_t>(std::floor(time / kBucket_s)); }

void LookaheadPairs::refill(double t) {
  // Most far entries go stale (a model replaced) before their time: they are dropped here
  // without ever entering the heap.
  while (!far_.empty() && static_cast<double>(far_.begin()->first) * kBucket_s <= t) {
    for (const Event& e : far_.begin()->second) {
      if (current(e)) queue_.push(e);
      else ++stats_.events_stale;
    }
    far_size_ -= far_.begin()->second.size();
    far_.erase(far_.begin());
  }
  near_end_ = std::max(near_end_, static_cast<double>(bucket_of(t) + 1) * kBucket_s);
}

void LookaheadPairs::process_until(double t) {
  refill(t);
  // The engine runs up to each queued time first: the edges it solves on the way queue
  // their entries, which may fall before that time and are run first, in time order.
  while (!queue_.empty() && queue_.top().time <= t) {
    kdt_.advance(std::max(kdt_.now(), queue_.top().time));
    sync_twins();
    const double until = kdt_.now();
    while (!queue_.empty() && queue_.top().time <= until) {
      const Event e = queue_.top();
      queue_.pop();
      run_event(e);
    }
  }
  kdt_.advance(t);
  sync_twins();
  while (!queue_.empty() && queue_.top().time <= t) {
    const Event e = queue_.top();
    queue_.pop();
    run_event(e);
  }
}

void LookaheadPairs::advance(double t) { process_until(std::max(t, kdt_.now())); }

void LookaheadPairs::report(Key key, double t, Point2 p, Vector2 v) {
  advance(t);
  ++stats_.reports;
  if (point_of_.size() <= key) point_of_.resize(key + 1, kNoPoint);
  PointId& id = point_of_[key];
  if (id == kNoPoint) {
    ++stats_.replaced;
    id = kdt_.insert(kdt_.now(), p + config_.lookahead_s * v, v);
    if (key_of_.size() <= id) {
      key_of_.resize(id + 1, 0);
      version_.resize(id + 1, 0);
      partners_.resize(id + 1);
      pending_.resize(id + 1);
      drift_seq_.resize(id + 1, 0);
      is_twin_.resize(id + 1, 0);
      replaced_at_.resize(id + 1, 0.0);
    }
    replaced_at_[id] = -std::numeric_limits<double>::infinity();
    key_of_[id] = key;
    ++version_[id];  // odd: live
    sync_twins();
    if (is_twin_[id]) return;
    // The insertion told the edges of its star before the point was live.
    const double now = kdt_.now();
    kdt_.for_each_neighbor(id, [&](PointId j) {
      if (live(j) && !is_twin_[j]) consider(id, j, now);
    });
    find_pairs(id);
    return;
  }
  // The report's deviation from the model over the look-ahead s in [0, T] and the next
  // K seconds: |Δp + Δv·(e + s)| ≤ max(|Δp|, |Δp + Δv·T|) + |Δv|·K (convex in s).
  const Vector2 dp = p - model_position(id);
  const Vector2 dv = v - kdt_.velocity(id);
  const double deviation =
      std::max(geometry::norm(dp), geometry::norm(dp + config_.lookahead_s * dv)) + geometry::norm(dv) * config_.keep_s;
  if (deviation <= config_.tolerance_m) {
    ++stats_.kept;
    pending_[id] = {p, v, kdt_.now()};
    push(kdt_.now() + config_.keep_s, Kind::Drift, id, id);
    drift_seq_[id] = next_seq_ - 1;
    return;
  }
  ++stats_.replaced;
  replaced_at_[id] = kdt_.now();
  replace_model(id, p, v);
}

double LookaheadPairs::last_replaced(Key key) const {
  if (key >= point_of_.size() || point_of_[key] == kNoPoint) return -std::numeric_limits<double>::infinity();
  return replaced_at_[point_of_[key]];
}

void LookaheadPairs::remove(Key key, double t) {
  if (key >= point_of_.size() || point_of_[key] == kNoPoint) return;
  advance(t);
  PointId& id = point_of_[key];
  ++version_[id];  // even: gone; its queued events are stale
  drift_seq_[id] = 0;
  forget_pairs(id);
  const bool hosted = !kdt_.twins_of(id).empty();
  kdt_.remove(id, kdt_.now());
  if (is_twin_[id]) {
    is_twin_[id] = 0;
    twins_.erase(std::find(twins_.begin(), twins_.end(), id));
  }
  if (hosted) twin_changes_seen_ = ~std::uint64_t{0};
  sync_twins();
  id = kNoPoint;
}

// ---------------------------------------------------------------------------------
// Checks

bool LookaheadPairs::is_valid() const {
  if (!kdt_.is_valid()) return false;
  const double now = kdt_.now();
  for (PointId a = 0; a < key_of_.size(); ++a) {
    if (!live(a) || is_twin_[a]) continue;
    for (PointId b = a + 1; b < key_of_.size(); ++b) {
      if (!live(b) || is_twin_[b]) continue;
      const Interval in = membership(a, b);
      // Strictly inside, by more than the rounding of the event times.
      if (in.begin < now - 1e-6 && now + 1e-6 < in.end && !holds(a, b)) return false;
    }
  }
  return true;
}

}  // namespace kew::testing
