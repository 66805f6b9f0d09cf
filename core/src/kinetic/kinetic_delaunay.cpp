#include "kew/kinetic/kinetic_delaunay.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "kew/kinetic/certificate.hpp"
#include "kew/kinetic/sturm.hpp"
#include "kew/util/gentle_growth.hpp"

namespace kew::kinetic {

using triangulation::AttachResult;
using triangulation::ccw;
using triangulation::cw;
using triangulation::EdgeState;
using triangulation::Face;
using triangulation::FaceIndex;
using triangulation::kInfiniteVertex;
using triangulation::kNoFace;
using triangulation::Trajectory;

namespace {
/// Early pops are re-solved from now + δ, δ doubling per retry from 1 ns; after
/// kMaxRetries the root is taken for numerical noise around a tangency.
constexpr double kFirstRetryDelay = 1e-9;
constexpr std::uint16_t kMaxRetries = 30;

/// The certificate, or the zero polynomial when every coefficient is within what the
/// rounding of the points' positions at `now` (and of their velocity differences) can
/// produce: the points are then cocircular (3 points: collinear) in real arithmetic
/// throughout, and the exact predicate on the rounded positions changes sign at instants
/// that no root of the polynomial tells (e.g. points flying apart from one common
/// point, whose positions are rounded on the scale of where they came from). Such edges
/// are watched like identically zero ones. `points`: the 4 (incircle) or 3 (orientation
/// or order) trajectories the certificate was built from, the first as the base.
Polynomial unless_rounding_noise(const Polynomial& certificate, std::initializer_list<const Trajectory*> points,
                                 double now) {
  if (certificate.is_zero()) return certificate;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const bool incircle = points.size() == 4;
  // The certificate is built on coordinates relative to one point. Their size is at
  // most L(τ) = spread + relative_speed·τ (m), and each carries an error of at most
  // E(τ) = 2·position_error + eps·L(τ), where position_error bounds (generously) the
  // rounding of origin + (now − t0)·velocity.
  const Trajectory& base = **points.begin();
  const Point2 base_now = base.at(now);
  double position_error = 0.0, spread = 0.0, relative_speed = 0.0;
  for (const Trajectory* T : points) {
    const Point2 p = T->at(now);
    const double lever = std::abs(now - T->t0);
    position_error = std::max(position_error, eps * (std::abs(T->origin.x) + std::abs(T->origin.y) + std::abs(p.x) +
                                                     std::abs(p.y) + 2.0 * lever * (std::abs(T->velocity.x) + std::abs(T->velocity.y))));
    spread = std::max({spread, std::abs(p.x - base_now.x), std::abs(p.y - base_now.y)});
    relative_speed = std::max({relative_speed, std::abs(T->velocity.x - base.velocity.x), std::abs(T->velocity.y - base.velocity.y)});
  }
  // First-order perturbation bound of the determinant, majorised coefficient by
  // coefficient, with a factor 2 to spare and 64 ulps of its own computation added:
  //   incircle (6 coordinates, each partial derivative ≤ 8L³): 192·L³·(E + 4·eps·L);
  //   orientation or order (4 coordinates, each partial ≤ L):   16·L·(E + 8·eps·L).
  const double slack = incircle ? 4.0 * eps : 8.0 * eps;
  const double error_now = 2.0 * position_error + (eps + slack) * spread;
  const double error_rate = (eps + slack) * relative_speed;
  const double scale = incircle ? 192.0 : 16.0;
  // Coefficients of L(τ)³ (incircle) or L(τ) (the others), from τ⁰ up.
  const std::array<double, 4> size_power =
      incircle ? std::array<double, 4>{spread * spread * spread, 3.0 * spread * spread * relative_speed,
                                       3.0 * spread * relative_speed * relative_speed,
                                       relative_speed * relative_speed * relative_speed}
               : std::array<double, 4>{spread, relative_speed, 0.0, 0.0};
  // From τ⁰ up: the value now settles almost every certificate, the derivative nearly
  // all the rest (a new edge starts near zero only after a flip at its root).
  for (int k = 0; k <= Polynomial::kMaxDegree; ++k) {
    const double from_value = k < 4 ? size_power[static_cast<unsigned>(k)] * error_now : 0.0;
    const double from_rate = k > 0 ? size_power[static_cast<unsigned>(k - 1)] * error_rate : 0.0;
    if (std::abs(certificate.coefficient(k)) > scale * (from_value + from_rate)) return certificate;
  }
  return {};
}
}  // namespace

KineticDelaunay::KineticDelaunay(const KineticConfig& config, double start_time)
    : config_(config), now_(start_time) {
  dt_.set_time(start_time);
  dt_.tds().set_observer(this);
  live_.push_back(false);
}

bool KineticDelaunay::contains(PointId id) const { return id < live_.size() && live_[id]; }

// ---------------------------------------------------------------------------------
// Face bookkeeping

void KineticDelaunay::face_created(FaceIndex f) {
  util::grow_to(schedule_, f + 1);
  schedule_[f] = FaceSchedule{};
  const std::uint32_t generation = dt_.tds().face(f).generation;
  dirty_faces_.emplace_back(f, generation);
}

void KineticDelaunay::face_destroyed(FaceIndex f) {
  for (int i = 0; i < 3; ++i) clear_edge(f, i, true);
}

void KineticDelaunay::clear_edge(FaceIndex f, int i, bool count_discard) {
  FaceSchedule& s = schedule_[f];
  const EventKind kind = s.kind[static_cast<unsigned>(i)];
  if (kind == EventKind::None) return;
  if (kind == EventKind::Failure || kind == EventKind::Approach) {
    --stats_.queue_now;
    if (count_discard && kind == EventKind::Failure) ++stats_.events_discarded;
  } else {
    --stats_.renewals_queued;
  }
  // The mirror side holds the same record.
  const FaceIndex g = dt_.tds().face(f).neighbor[static_cast<unsigned>(i)];
  const int j = dt_.tds().mirror_index(f, i);
  for (auto [face, edge] : {std::pair{f, i}, std::pair{g, j}}) {
    FaceSchedule& r = schedule_[face];
    r.kind[static_cast<unsigned>(edge)] = EventKind::None;
    r.time[static_cast<unsigned>(edge)] = kNever;
    r.seq[static_cast<unsigned>(edge)] = 0;
  }
}

double KineticDelaunay::earliest_failure(FaceIndex f) const {
  const FaceSchedule& s = schedule_[f];
  double t = kNever;
  // An approach destroys faces like a failure does, so it bounds §8.3 windows too.
  for (int i = 0; i < 3; ++i) {
    const EventKind kind = s.kind[static_cast<unsigned>(i)];
    if (kind == EventKind::Failure || kind == EventKind::Approach) t = std::min(t, s.time[static_cast<unsigned>(i)]);
  }
  return t;
}

void KineticDelaunay::schedule_edge(double time, FaceIndex f, int i, EventKind kind, std::uint16_t retries) {
  const std::uint64_t seq = queue_.push(time, f, static_cast<std::uint8_t>(i), kind, retries);
  const FaceIndex g = dt_.tds().face(f).neighbor[static_cast<unsigned>(i)];
  const int j = dt_.tds().mirror_index(f, i);
  for (auto [face, edge] : {std::pair{f, i}, std::pair{g, j}}) {
    FaceSchedule& r = schedule_[face];
    r.kind[static_cast<unsigned>(edge)] = kind;
    r.time[static_cast<unsigned>(edge)] = time;
    r.seq[static_cast<unsigned>(edge)] = seq;
  }
  if (kind == EventKind::Failure || kind == EventKind::Approach) {
    ++stats_.queue_now;
    stats_.queue_max = std::max(stats_.queue_max, stats_.queue_now);
  } else {
    ++stats_.renewals_queued;
  }
}

bool KineticDelaunay::is_live(const Entry& e) const {
  if (e.kind == EventKind::TwinRelease) return twins_.release_seq(e.subject) == e.seq;
  if (e.kind == EventKind::Drift) return drift_seq_[e.subject] == e.seq;
  return dt_.tds().face(e.subject).alive && schedule_[e.subject].seq[e.edge] == e.seq;
}

// ---------------------------------------------------------------------------------
// Certificates

Polynomial KineticDelaunay::edge_certificate(FaceIndex f, int i) const {
  // Mirrors DelaunayTriangulation::edge_state: positive exactly when violated.
  const auto& tds = dt_.tds();
  const Face& face = tds.face(f);
  const FaceIndex g = face.neighbor[static_cast<unsigned>(i)];
  const int j = tds.mirror_index(f, i);
  const PointId c = face.vertex[static_cast<unsigned>(i)];
  const PointId a = face.vertex[static_cast<unsigned>(ccw(i))];
  const PointId b = face.vertex[static_cast<unsigned>(cw(i))];
  const PointId d = tds.face(g).vertex[static_cast<unsigned>(j)];
  const auto& T = [this](PointId v) -> const Trajectory& { return dt_.trajectory(v); };
  if (a == kInfiniteVertex || b == kInfiniteVertex) {
    if (c == d) return {};
    const PointId x = a == kInfiniteVertex ? b : a;
    const Polynomial turn = a == kInfiniteVertex ? orientation_polynomial(T(x), T(c), T(d), now_)
                                                 : orientation_polynomial(T(x), T(d), T(c), now_);
    // Hull vertices moving on one exact line: certify their order instead. (Only an
    // exactly zero turn means that; a turn that is rounding noise is watched.)
    if (turn.is_zero()) return unless_rounding_noise(dot_polynomial(T(x), T(c), T(d), now_), {&T(x), &T(c), &T(d)}, now_);
    return unless_rounding_noise(turn, {&T(x), &T(c), &T(d)}, now_);
  }
  if (c == kInfiniteVertex && d == kInfiniteVertex) return {};
  if (d == kInfiniteVertex) return unless_rounding_noise(-1.0 * orientation_polynomial(T(a), T(b), T(c), now_), {&T(a), &T(b), &T(c)}, now_);
  if (c == kInfiniteVertex) return unless_rounding_noise(-1.0 * orientation_polynomial(T(b), T(a), T(d), now_), {&T(b), &T(a), &T(d)}, now_);
  return unless_rounding_noise(incircle_polynomial(T(a), T(b), T(c), T(d), now_), {&T(a), &T(b), &T(c), &T(d)}, now_);
}

double KineticDelaunay::approach_offset(FaceIndex f, int i) const {
  const Face& face = dt_.tds().face(f);
  const PointId a = face.vertex[static_cast<unsigned>(ccw(i))];
  const PointId b = face.vertex[static_cast<unsigned>(cw(i))];
  if (a == kInfiniteVertex || b == kInfiniteVertex) return kNever;
  const double r = config_.twin_release_distance_m;
  const Vector2 gap = dt_.position(a) - dt_.position(b);
  const double c = geometry::dot(gap, gap) - r * r;
  if (c < 0.0) return 0.0;
  const Vector2 drift = dt_.trajectory(a).velocity - dt_.trajectory(b).velocity;
  const double b_half = geometry::dot(gap, drift);
  if (!(b_half < 0.0)) return kNever;  // not approaching
  const double speed2 = geometry::dot(drift, drift);
  const double disc = b_half * b_half - speed2 * c;
  if (disc < 0.0) return kNever;  // their closest approach is wider than r
  // Smaller root of |gap + drift·τ|² = r², in the form without cancellation.
  return c / (-b_half + std::sqrt(disc));
}

void KineticDelaunay::solve_edge(FaceIndex f, int i, double from_offset, std::uint16_t retries) {
  solve_edge(f, i, from_offset, retries, edge_certificate(f, i));
}

void KineticDelaunay::solve_edge(FaceIndex f, int i, double from_offset, std::uint16_t retries,
                                 const Polynomial& certificate) {
  const FaceIndex g = dt_.tds().face(f).neighbor[static_cast<unsigned>(i)];
  double end = now_ + config_.horizon_s;
  if (config_.reduce_redundant_events) end = std::min({end, earliest_failure(f), earliest_failure(g)});
  watch_degenerate(f, i, certificate.is_zero());
  // Two ends about to pass through each other: every certificate around them vanishes
  // at the meeting instant, which no flip sequence can follow exactly. Merge them into
  // twins just before instead; the certificate only matters until then.
  const double approach = approach_offset(f, i);
  if (approach < end - now_) {
    if (!certificate.is_zero() && from_offset < approach) {
      ++stats_.certificates_solved;
      const Crossing crossing = first_positive_crossing(certificate, from_offset, approach);
      stats_.tangencies_ignored += static_cast<std::uint64_t>(crossing.tangencies);
      if (crossing.violated_at_start || crossing.found) {
        const double at = crossing.violated_at_start ? now_ + from_offset : now_ + crossing.time;
        ++stats_.events_computed;
        schedule_edge(at, f, i, EventKind::Failure, retries);
        return;
      }
    }
    ++stats_.approaches_scheduled;
    schedule_edge(now_ + approach, f, i, EventKind::Approach, 0);
    return;
  }
  if (certificate.is_zero()) {
    // No event can be computed (the edge is watched if it constrains anything), but an
    // approach beyond the window must still be looked for when the window closes.
    if (std::isfinite(approach) && std::isfinite(end))
      schedule_edge(std::max(end, now_), f, i, EventKind::Renewal, 0);
    return;
  }
  const double window = end - now_;
  if (!(window > from_offset)) {
    ++stats_.certificates_solved;
    // Nothing to examine before the window closes: re-examine when it does.
    if (std::isfinite(end)) schedule_edge(std::max(end, now_), f, i, EventKind::Renewal, 0);
    return;
  }
  const double lazy = config_.lazy_window_s;
  if (lazy > from_offset && window > lazy && certainly_negative(certificate, lazy)) {
    // Valid until now + lazy for certain, the same answer a horizon of lazy would give.
    ++stats_.certificates_deferred;
    schedule_edge(now_ + lazy, f, i, EventKind::Renewal, 0);
    return;
  }
  ++stats_.certificates_solved;
  const Crossing crossing = first_positive_crossing(certificate, from_offset, window);
  stats_.tangencies_ignored += static_cast<std::uint64_t>(crossing.tangencies);
  if (crossing.violated_at_start || crossing.found) {
    const double at = crossing.violated_at_start ? now_ + from_offset : now_ + crossing.time;
    ++stats_.events_computed;
    schedule_edge(at, f, i, EventKind::Failure, retries);
    return;
  }
  if (std::isfinite(end)) schedule_edge(end, f, i, EventKind::Renewal, 0);
}

void KineticDelaunay::watch_degenerate(FaceIndex f, int i, bool zero_certificate) {
  const auto& tds = dt_.tds();
  const Face& face = tds.face(f);
  const PointId c = face.vertex[static_cast<unsigned>(i)];
  const PointId d = tds.face(face.neighbor[static_cast<unsigned>(i)]).vertex[static_cast<unsigned>(tds.mirror_index(f, i))];
  // Edges that constrain nothing (segments of a flat chain, the ends of one) have no
  // certificate at all, rather than a degenerate one.
  const bool unconstrained = c == d || (c == kInfiniteVertex && d == kInfiniteVertex);
  std::uint8_t& mask = schedule_[f].zero_certificate;
  const auto bit = static_cast<std::uint8_t>(1u << i);
  if (zero_certificate && !unconstrained) {
    if (mask == 0) degenerate_faces_.emplace_back(f, face.generation);
    mask = static_cast<std::uint8_t>(mask | bit);
  } else {
    mask = static_cast<std::uint8_t>(mask & ~bit);
  }
}

bool KineticDelaunay::flip_degenerate_edges() {
  if (degenerate_faces_.empty()) return false;
  const auto& tds = dt_.tds();
  std::vector<std::pair<FaceIndex, int>> seeds;
  std::size_t kept = 0;
  for (const auto& [f, generation] : degenerate_faces_) {
    const Face& face = tds.face(f);
    const std::uint8_t mask = schedule_[f].zero_certificate;
    if (!face.alive || face.generation != generation || mask == 0) continue;
    degenerate_faces_[kept++] = {f, generation};
    for (int i = 0; i < 3; ++i)
      if ((mask >> i) & 1u && dt_.edge_state(f, i) == EdgeState::Violated) seeds.emplace_back(f, i);
  }
  degenerate_faces_.resize(kept);
  if (seeds.empty()) return false;
  std::vector<std::pair<FaceIndex, int>> stuck;
  stats_.degenerate_flips += dt_.make_locally_delaunay(seeds, &stuck);
  std::vector<PointId> suspects;
  for (const auto& [f, i] : stuck) {
    if (!tds.face(f).alive) continue;
    suspects.insert(suspects.end(), tds.face(f).vertex.begin(), tds.face(f).vertex.end());
  }
  if (!suspects.empty()) repair_around(suspects);
  schedule_dirty_faces();
  return true;
}

void KineticDelaunay::schedule_dirty_faces() {
  if (dirty_faces_.empty()) return;
  ++dirty_round_;
  util::grow_to(dirty_mark_, schedule_.size(), std::uint32_t{0});
  const auto& tds = dt_.tds();
  // Keep only faces still alive in the generation they were created in.
  std::size_t kept = 0;
  for (const auto& [f, generation] : dirty_faces_) {
    if (!tds.face(f).alive || tds.face(f).generation != generation || dirty_mark_[f] == dirty_round_) continue;
    dirty_mark_[f] = dirty_round_;
    dirty_faces_[kept++] = {f, generation};
  }
  dirty_faces_.resize(kept);
  const auto faces = std::move(dirty_faces_);
  dirty_faces_.clear();
  for (const auto& [f, generation] : faces) {
    for (int i = 0; i < 3; ++i) {
      const FaceIndex g = tds.face(f).neighbor[static_cast<unsigned>(i)];
      // An edge between two dirty faces is solved once, from the smaller index.
      if (dirty_mark_[g] == dirty_round_ && g < f) continue;
      if (schedule_[f].kind[static_cast<unsigned>(i)] != EventKind::None) clear_edge(f, i, true);
      solve_edge(f, i, 0.0, 0);
      tell_edge_listener(f, i);
    }
  }
}

// ---------------------------------------------------------------------------------
// Time

void KineticDelaunay::set_now(double t) {
  now_ = t;
  dt_.set_time(t);
}

void KineticDelaunay::advance_sampled(double t) {
  advance(t);
  // Sampled here, by the points' operations, and not by advance(): how often a caller
  // advances the clock between them (a batch's end, a tick) must not move the mean.
  stats_.queue_sum += static_cast<double>(stats_.queue_now);
  ++stats_.queue_samples;
}

void KineticDelaunay::advance(double t) {
  assert(!(t < now_) && "the engine's clock only moves forward");
  if (t < now_) t = now_;
  do {
    while (!queue_.empty() && queue_.top().time <= t) {
      const Entry e = queue_.pop();
      if (!is_live(e)) continue;
      set_now(std::max(now_, e.time));
      execute(e);
      schedule_dirty_faces();
    }
    set_now(t);
    // Flips of degenerate edges may schedule failures already due at t: loop.
  } while (flip_degenerate_edges());
  queue_.compact(stats_.queue_now + stats_.renewals_queued + stats_.drifts_queued,
                 [this](const Entry& e) { return is_live(e); });
}

void KineticDelaunay::execute(const Entry& e) {
  switch (e.kind) {
    case EventKind::Failure:
      execute_failure(e);
      return;
    case EventKind::Renewal:
      ++stats_.renewals;
      clear_edge(e.subject, e.edge, false);
      solve_edge(e.subject, e.edge, 0.0, 0);
      return;
    case EventKind::Approach:
      execute_approach(e);
      return;
    case EventKind::Drift:
      execute_drift(e.subject);
      return;
    case EventKind::TwinRelease: {
      const PointId id = e.subject;
      twins_.set_release_seq(id, 0);
      if (!twins_.is_twin(id)) return;
      const PointId host = twins_.host_of(id);
      const Vector2 gap = dt_.position(id) - dt_.position(host);
      const double r = config_.twin_release_distance_m;
      if (geometry::dot(gap, gap) < r * r) {
        // Still closer than r after rounding: look again later, so that a released
        // twin is never merged straight back by approach_offset().
        schedule_twin_release(id);
        return;
      }
      twins_.unlink(id);
      ++stats_.twins_released;
      attach_point(id);
      return;
    }
    case EventKind::None:
      return;
  }
}

void KineticDelaunay::execute_failure(const Entry& e) {
  const FaceIndex f = e.subject;
  const int i = e.edge;
  clear_edge(f, i, false);
  const Face& quad = dt_.tds().face(f);
  const FaceIndex across = quad.neighbor[static_cast<unsigned>(i)];
  if (!dt_.is_positive(f) || !dt_.is_positive(across)) {
    // A face of the quadrilateral is flat or inverted: points passed through each other
    // (every certificate around them vanished at one instant). Repair locally.
    repair_quadrilateral(f, i);
    return;
  }
  const EdgeState state = dt_.edge_state(f, i);
  if (state != EdgeState::Violated) {
    // The root was found a little before the exact predicates agree: look again just later.
    ++stats_.events_early;
    if (e.retries >= kMaxRetries) {
      ++stats_.tangencies_ignored;
      solve_edge(f, i, 1.0, 0);
      return;
    }
    const double delay = std::ldexp(kFirstRetryDelay, e.retries);
    solve_edge(f, i, delay, static_cast<std::uint16_t>(e.retries + 1));
    return;
  }
  if (dt_.is_flippable(f, i)) {
    dt_.tds().flip(f, i);
    ++stats_.events_executed;
    return;
  }
  // Violated but not flippable: the neighbourhood is degenerate (points passing through
  // each other, collinear overtakes). Repair it locally.
  repair_quadrilateral(f, i);
}

void KineticDelaunay::execute_approach(const Entry& e) {
  const FaceIndex f = e.subject;
  const int i = e.edge;
  clear_edge(f, i, false);
  const Face& face = dt_.tds().face(f);
  PointId keep = face.vertex[static_cast<unsigned>(ccw(i))];
  PointId leave = face.vertex[static_cast<unsigned>(cw(i))];
  // The time was computed in floating point: accept anything near r, else look again.
  const Vector2 gap = dt_.position(keep) - dt_.position(leave);
  const double r = config_.twin_release_distance_m;
  if (geometry::dot(gap, gap) > 4.0 * r * r) {
    solve_edge(f, i, 0.0, 0);
    return;
  }
  // Deterministic choice: the vertex hosting more twins stays (fewer moves), then the
  // lower index.
  const std::size_t leave_twins = twins_.twins_of(leave).size(), keep_twins = twins_.twins_of(keep).size();
  if (leave_twins > keep_twins || (leave_twins == keep_twins && leave < keep)) std::swap(keep, leave);
  if (!detach_vertex(leave)) ++stats_.repairs;
  ++stats_.approaches_merged;
  merge_into(leave, keep);
}

void KineticDelaunay::repair_quadrilateral(FaceIndex f, int i) {
  const auto& tds = dt_.tds();
  const Face& face = tds.face(f);
  std::vector<PointId> suspects(face.vertex.begin(), face.vertex.end());
  suspects.push_back(tds.face(face.neighbor[static_cast<unsigned>(i)]).vertex[static_cast<unsigned>(tds.mirror_index(f, i))]);
  repair_around(suspects);
}

// ---------------------------------------------------------------------------------
// Attaching, detaching, twins

void KineticDelaunay::tell_edge_listener(FaceIndex f, int i) {
  if (!edge_listener_) return;
  const auto& face = dt_.tds().face(f);
  const PointId a = face.vertex[static_cast<unsigned>(ccw(i))];
  const PointId b = face.vertex[static_cast<unsigned>(cw(i))];
  if (a != triangulation::kInfiniteVertex && b != triangulation::kInfiniteVertex && a != b)
    edge_listener_->edge_solved(a, b);
}

PointId KineticDelaunay::attached_neighbour(PointId id) const {
  const PointId vertex = host_of(id);
  if (vertex != id) return vertex;
  const triangulation::Tds& tds = dt_.tds();
  if (!tds.is_attached(vertex)) return kNoPoint;
  PointId found = kNoPoint;
  tds.for_each_adjacent_vertex(vertex, [&](PointId w) {
    if (found == kNoPoint && w != kInfiniteVertex) found = w;
  });
  return found;
}

void KineticDelaunay::attach_point(PointId id, FaceIndex hint) {
  PointId same = kNoPoint;
  AttachResult result = dt_.attach(id, &same, hint);
  if (result == AttachResult::NotDelaunay) {
    // The neighbourhood is not Delaunay at now (a missed or degenerate event): repair, retry.
    audit_and_repair();
    result = dt_.attach(id, &same);
    if (result == AttachResult::NotDelaunay) {
      ++stats_.repairs;
      rebuild_triangulation();
      result = dt_.attach(id, &same);
    }
  }
  if (result == AttachResult::Duplicate) make_twin(id, same);
  schedule_dirty_faces();
}

void KineticDelaunay::detach_point(PointId id) {
  if (twins_.is_twin(id)) {
    twins_.unlink(id);
    return;
  }
  const std::vector<PointId> orphans = twins_.release_all(id);
  if (!detach_vertex(id)) ++stats_.repairs;
  // Twins of a removed vertex take its place: the first is attached, the rest re-twin.
  for (const PointId w : orphans) attach_point(w);
}

void KineticDelaunay::make_twin(PointId id, PointId host) {
  twins_.make_twin(id, host);
  ++stats_.twins_created;
  schedule_twin_release(id);
}

void KineticDelaunay::schedule_twin_release(PointId id) {
  const PointId host = twins_.host_of(id);
  twins_.set_release_seq(id, 0);
  const Vector2 gap = dt_.position(id) - dt_.position(host);
  const Vector2 drift = dt_.trajectory(id).velocity - dt_.trajectory(host).velocity;
  const double speed2 = geometry::dot(drift, drift);
  if (speed2 == 0.0) return;  // moving together: twins until one of them changes
  // Smallest τ > 0 with |gap + drift·τ| = release distance.
  const double r = config_.twin_release_distance_m;
  const double b = geometry::dot(gap, drift);
  const double c = geometry::dot(gap, gap) - r * r;
  const double disc = std::max(0.0, b * b - speed2 * c);
  const double tau = std::max((-b + std::sqrt(disc)) / speed2, kFirstRetryDelay);
  // On a far epoch now + tau can round back to now; a release looked at again at the
  // same instant would find the same gap forever.
  const double at = now_ + tau;
  const std::uint64_t seq = queue_.push(at > now_ ? at : std::nextafter(now_, kNever), id, 0, EventKind::TwinRelease, 0);
  twins_.set_release_seq(id, seq);
}

bool KineticDelaunay::detach_vertex(PointId vertex) {
  const triangulation::DetachResult detached = dt_.detach(vertex);
  adopt_evictions(detached.evicted);
  if (!detached.hole_triangulated) ++stats_.rebuilds;
  return detached.hole_triangulated;
}

void KineticDelaunay::rebuild_triangulation() {
  ++stats_.rebuilds;
  adopt_evictions(dt_.rebuild());
}

void KineticDelaunay::adopt_evictions(const std::vector<triangulation::Eviction>& evicted) {
  // The evicted vertex may host twins of its own: merge_into takes them along.
  for (const auto& [vertex, same] : evicted) merge_into(vertex, same);
}

void KineticDelaunay::merge_into(PointId vertex, PointId host) {
  ++stats_.twins_created;  // vertex only: its twins are not new twins, they change host
  for (const PointId w : twins_.merge_into(vertex, host)) schedule_twin_release(w);
}

// ---------------------------------------------------------------------------------
// Robustness

void KineticDelaunay::repair_around(const std::vector<PointId>& vertices) {
  ++stats_.repairs;
  auto& tds = dt_.tds();
  std::vector<std::pair<FaceIndex, int>> seeds;
  std::vector<PointId> reinsert;
  for (const PointId v : vertices) {
    if (v == kInfiniteVertex || !tds.is_attached(v)) continue;
    tds.incident_faces(v, scratch_faces_);
    for (const FaceIndex f : scratch_faces_) {
      if (!dt_.is_positive(f))
        for (const PointId w : tds.face(f).vertex)
          if (w != kInfiniteVertex) reinsert.push_back(w);
      for (int i = 0; i < 3; ++i) seeds.emplace_back(f, i);
    }
  }
  std::sort(reinsert.begin(), reinsert.end());
  reinsert.erase(std::unique(reinsert.begin(), reinsert.end()), reinsert.end());
  if (reinsert.empty()) {
    std::vector<std::pair<FaceIndex, int>> stuck;
    stats_.repair_flips += dt_.make_locally_delaunay(seeds, &stuck);
    if (stuck.empty()) return;
    for (const auto& [f, i] : stuck) {
      if (!tds.face(f).alive) continue;
      for (const PointId w : tds.face(f).vertex)
        if (w != kInfiniteVertex) reinsert.push_back(w);
    }
    std::sort(reinsert.begin(), reinsert.end());
    reinsert.erase(std::unique(reinsert.begin(), reinsert.end()), reinsert.end());
  }
  // Take the suspects out one at a time, each time only while the rest of their
  // neighbourhood is valid, then put them back at their current positions.
  for (const PointId v : reinsert) {
    if (!dt_.is_attached(v)) continue;
    ++stats_.repair_reinsertions;
    const std::vector<PointId> orphans = twins_.release_all(v);
    detach_vertex(v);
    PointId same = kNoPoint;
    AttachResult result = dt_.attach(v, &same);
    if (result == AttachResult::NotDelaunay) {
      rebuild_triangulation();
      result = dt_.attach(v, &same);
    }
    if (result == AttachResult::Duplicate) make_twin(v, same);
    for (const PointId w : orphans) attach_point(w);
  }
  if (dt_.audit().violations() != 0) rebuild_triangulation();
}

KineticAudit KineticDelaunay::audit_and_repair() {
  KineticAudit result;
  const auto report = dt_.audit();
  result.violations_found = report.violations();
  if (result.violations_found == 0) return result;
  stats_.repairs += result.violations_found;
  // Local first: Lawson flips on violated edges, reinsertion around inverted faces.
  std::vector<PointId> suspects;
  const auto& tds = dt_.tds();
  if (report.combinatorially_valid) {
    for (FaceIndex f = 0; f < tds.face_capacity(); ++f) {
      if (!tds.face(f).alive) continue;
      bool bad = !dt_.is_positive(f);
      for (int i = 0; i < 3 && !bad; ++i) bad = dt_.edge_state(f, i) == EdgeState::Violated;
      if (bad) suspects.insert(suspects.end(), tds.face(f).vertex.begin(), tds.face(f).vertex.end());
    }
    std::sort(suspects.begin(), suspects.end());
    suspects.erase(std::unique(suspects.begin(), suspects.end()), suspects.end());
    --stats_.repairs;  // repair_around counts itself
    repair_around(suspects);
  }
  if (dt_.audit().violations() != 0) rebuild_triangulation();
  result.violations_unrepaired = dt_.audit().violations();
  schedule_dirty_faces();
  return result;
}

bool KineticDelaunay::is_valid() const {
  if (!dt_.is_valid() || !twins_.is_valid()) return false;
  // Every live point is either a triangulation vertex or a twin of a live one.
  for (PointId id = 1; id < live_.size(); ++id) {
    if (!live_[id]) continue;
    if (twins_.is_twin(id) ? !live_[twins_.host_of(id)] : !dt_.is_attached(id)) return false;
  }
  return true;
}

void KineticDelaunay::continue_statistics(const KineticStatistics& earlier) {
  const KineticStatistics own = stats_;
  stats_ = earlier;
  ++stats_.renumberings;
  stats_.queue_now = own.queue_now;
  stats_.queue_max = std::max(earlier.queue_max, own.queue_max);
  stats_.renewals_queued = own.renewals_queued;
  stats_.drifts_queued = own.drifts_queued;
}

void add_statistics(KineticStatistics& total, const KineticStatistics& part) {
  const std::size_t largest = std::max(total.queue_max, part.queue_max);
  total.certificates_solved += part.certificates_solved;
  total.certificates_deferred += part.certificates_deferred;
  total.certificates_kept += part.certificates_kept;
  total.events_computed += part.events_computed;
  total.events_executed += part.events_executed;
  total.events_discarded += part.events_discarded;
  total.events_early += part.events_early;
  total.tangencies_ignored += part.tangencies_ignored;
  total.renewals += part.renewals;
  total.insertions += part.insertions;
  total.removals += part.removals;
  total.updates += part.updates;
  total.velocity_updates += part.velocity_updates;
  total.kept_updates += part.kept_updates;
  total.reinsertions += part.reinsertions;
  total.drift_reinsertions += part.drift_reinsertions;
  total.repairs += part.repairs;
  total.repair_flips += part.repair_flips;
  total.degenerate_flips += part.degenerate_flips;
  total.repair_reinsertions += part.repair_reinsertions;
  total.rebuilds += part.rebuilds;
  total.renumberings += part.renumberings;
  total.twins_created += part.twins_created;
  total.twins_released += part.twins_released;
  total.approaches_scheduled += part.approaches_scheduled;
  total.approaches_merged += part.approaches_merged;
  total.queue_now += part.queue_now;
  total.renewals_queued += part.renewals_queued;
  total.drifts_queued += part.drifts_queued;
  total.queue_sum += part.queue_sum;
  total.queue_samples += part.queue_samples;
  total.queue_max = largest;
}

}  // namespace kew::kinetic
