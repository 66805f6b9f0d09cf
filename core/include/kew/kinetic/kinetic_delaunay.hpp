#pragma once
// Thresholded kinetic Delaunay triangulation with tolerance-based reinsertion
// (thesis ch. 6–8, 10; design §2, §7). Points move linearly in the projected plane; the
// triangulation is kept Delaunay for their positions as time advances by processing
// certificate failures (edge flips) in time order.

#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "kew/geometry/vector2.hpp"
#include "kew/kinetic/event_queue.hpp"
#include "kew/kinetic/polynomial.hpp"
#include "kew/kinetic/twin_registry.hpp"
#include "kew/triangulation/delaunay.hpp"
#include "kew/util/name_table.hpp"

namespace kew::kinetic {

using geometry::Point2;
using geometry::Vector2;
inline constexpr double kNever = std::numeric_limits<double>::infinity();

/// How the reinsertion tolerance τ is measured (thesis Eq. 10.1).
enum class ToleranceMode {
  Absolute,  ///< |measured − predicted| ≤ τ metres (design §2.3, the default)
  Relative,  ///< |measured − predicted| / |measured| ≤ τ (the thesis' form, unitless)
};
/// The names of `tolerance_mode = ...`.
inline constexpr util::NameTable<ToleranceMode, 2> kToleranceModeNames({{
    {ToleranceMode::Absolute, "absolute"},
    {ToleranceMode::Relative, "relative"},
}});

struct KineticConfig {
  /// Event-time threshold H (s, > 0): failures later than now + H are not computed;
  /// the certificate is re-examined at now + H instead (thesis §10.4, design §2.4).
  double horizon_s = kNever;
  /// Reinsertion tolerance τ (metres, or unitless in Relative mode), ≥ 0.
  double tolerance = 0.0;
  ToleranceMode tolerance_mode = ToleranceMode::Absolute;
  /// Solve a new certificate only up to the earliest event of its two triangles (§8.3).
  bool reduce_redundant_events = true;
  /// Points closer than this (metres, > 0) are kept as twins of one triangulation
  /// vertex: exact duplicates, and pairs whose paths cross within this distance, which
  /// are merged when they come this close (before they meet) and released when they are
  /// this far apart again. Far above coordinate rounding (≈ 1e-11 m at 100 km), so an
  /// exact meeting in the model is always caught; small enough to be invisible to the
  /// probe.
  double twin_release_distance_m = 1e-3;
  /// Lazy certificates (design §2.4, s, ≥ 0; 0: off): a certificate the certified bound
  /// proves valid over [now, now + lazy_window_s] is not solved further; that window is
  /// its life and it is re-examined at its end. Updates re-solve the certificates around
  /// a point, several times a radar period, so most never need more.
  double lazy_window_s = 0.0;
  /// Kept models (design §2.3, s, ≥ 0; 0: off; Absolute tolerance only): an update
  /// whose report stays within τ of the point's model position for at least this long —
  /// |p − model| + |v − model velocity|·s ≤ τ — changes nothing in the triangulation;
  /// the report is remembered, and if no later update comes first, a Drift event at the
  /// moment the bound runs out reinserts the point on the report's trajectory. Either
  /// way the model never lags its latest report by more than τ. A radar period or more:
  /// each update then costs a comparison, not the rescheduling of its star.
  double keep_model_s = 0.0;
};

/// Counters an engine user can read. Events are certificate failures.
struct KineticStatistics {
  std::uint64_t certificates_solved = 0;  ///< Sturm solves run
  std::uint64_t certificates_deferred = 0;  ///< proved valid over the lazy window, not solved further
  /// Certificates of a velocity-only update's star proved valid, on the new velocity, up
  /// to the renewal already scheduled for them, which is kept instead of solving again.
  std::uint64_t certificates_kept = 0;
  std::uint64_t events_computed = 0;      ///< failures found and scheduled
  std::uint64_t events_executed = 0;      ///< failures that flipped an edge
  std::uint64_t events_discarded = 0;     ///< scheduled failures descheduled before their time
  std::uint64_t events_early = 0;         ///< popped before the exact predicate agreed; re-solved
  std::uint64_t tangencies_ignored = 0;   ///< even-multiplicity roots (no event, Lemma 6)
  std::uint64_t renewals = 0;             ///< expired windows re-examined (threshold or §8.3 clip)
  std::uint64_t insertions = 0;
  std::uint64_t removals = 0;
  std::uint64_t updates = 0;
  std::uint64_t velocity_updates = 0;     ///< updates within τ: velocity changed, position kept
  std::uint64_t kept_updates = 0;         ///< updates within τ for keep_model_s: model unchanged
  std::uint64_t reinsertions = 0;         ///< updates beyond τ: removed and reinserted
  std::uint64_t drift_reinsertions = 0;   ///< kept models replaced by their report at the deadline
  std::uint64_t repairs = 0;              ///< defects found by audits or degenerate events and fixed
  std::uint64_t repair_flips = 0;
  /// Flips of edges whose certificate is identically zero, or no larger than the
  /// rounding of the positions can make it (points moving so as to stay exactly
  /// cocircular, e.g. converging radially at one speed, or flying apart from one common
  /// point): no event can be computed for them, so they are checked exactly whenever
  /// advance() returns.
  std::uint64_t degenerate_flips = 0;
  std::uint64_t repair_reinsertions = 0;
  std::uint64_t rebuilds = 0;             ///< full retriangulations (last-resort repair)
  /// Engines replaced by one built in memory order (the Pipeline's renumbering, design
  /// §8.3); their own insertions are not counted above.
  std::uint64_t renumberings = 0;
  std::uint64_t twins_created = 0;        ///< points made twins: exact duplicates and approaches
  std::uint64_t twins_released = 0;       ///< twins reinserted once twin_release_distance_m apart
  /// Approach entries scheduled: edges whose two ends come within
  /// twin_release_distance_m inside the edge's window (counted again when the edge is
  /// rescheduled, like failures).
  std::uint64_t approaches_scheduled = 0;
  std::uint64_t approaches_merged = 0;    ///< of those, merged into twins (also in twins_created)
  std::size_t queue_now = 0;              ///< failures and approaches scheduled now
  std::size_t queue_max = 0;
  std::size_t renewals_queued = 0;        ///< renewal entries scheduled now
  std::size_t drifts_queued = 0;          ///< Drift deadlines scheduled now
  double queue_sum = 0.0;                 ///< Σ queue_now over samples (before and after each insert, update, removal)
  std::uint64_t queue_samples = 0;
  double queue_mean() const { return queue_samples ? queue_sum / static_cast<double>(queue_samples) : 0.0; }
};

/// Adds the counters of `part` to `total` (engines of several zones): counts and the
/// current queue sizes are summed, queue_max is the larger of the two.
void add_statistics(KineticStatistics& total, const KineticStatistics& part);

/// What update() did.
enum class UpdateKind {
  Kept,          ///< within τ for KineticConfig::keep_model_s: the model stays as it was
  VelocityOnly,  ///< within τ: position kept, velocity replaced
  Reinserted,    ///< beyond τ: removed and reinserted at the report
};

/// Told of the Delaunay edges whose certificates the engine computes (design §2.7): every
/// edge between two triangulation vertices that comes to exist (insertion, reinsertion,
/// flip, repair, rebuild) is told at the engine time it appears, and edges around a
/// point whose motion changed are told again. Twins are not vertices: their edges are
/// their host's. For structures that must see each edge before it can matter, such as
/// the look-ahead pairs prototype of kinetic detection (tests/support/lookahead_pairs.hpp).
class EdgeListener {
 public:
  virtual ~EdgeListener() = default;
  /// a ≠ b, both triangulation vertices; called from inside advance(), insert(),
  /// update() and remove(), which must not be re-entered.
  virtual void edge_solved(PointId a, PointId b) = 0;
};

/// Result of an audit at the current time.
struct KineticAudit {
  std::size_t violations_found = 0;
  std::size_t violations_unrepaired = 0;
};

class KineticDelaunay final : private triangulation::FaceObserver {
 public:
  /// `start_time` in seconds, on any epoch the caller keeps consistently.
  explicit KineticDelaunay(const KineticConfig& config = {}, double start_time = 0.0);
  KineticDelaunay(const KineticDelaunay&) = delete;
  KineticDelaunay& operator=(const KineticDelaunay&) = delete;

  /// Processes every event up to time t (s, ≥ now()) in time order; now() becomes t.
  void advance(double t);
  double now() const { return now_; }

  /// Adds a point at position p (m) moving at velocity v (m/s) at time t (≥ now()).
  PointId insert(double t, Point2 p, Vector2 v);
  /// Removes a point at time t (≥ now()).
  void remove(PointId id, double t);
  /// A new measurement of a point at time t (≥ now()): within the tolerance the
  /// predicted position is kept and only the velocity changes (or, with keep_model_s,
  /// nothing changes while the model stays within τ of the measurement); beyond it the
  /// point is removed and reinserted at p (Eq. 10.1).
  UpdateKind update(PointId id, double t, Point2 p, Vector2 v);

  bool contains(PointId id) const;
  std::size_t size() const { return live_points_; }
  /// Model position at time t (m): the last accepted position extrapolated linearly.
  /// Within τ of the latest update's p + v·(t − t_update) until the next update.
  Point2 position(PointId id, double t) const { return dt_.trajectory(id).at(t); }
  Point2 position_now(PointId id) const { return dt_.trajectory(id).at(now_); }
  Vector2 velocity(PointId id) const { return dt_.trajectory(id).velocity; }

  /// Calls f(neighbour) for every Delaunay neighbour of id, counting twins (points
  /// within twin_release_distance_m of their host, not yet separated) as neighbours of
  /// each other and of the neighbours of their host.
  template <class F>
  void for_each_neighbor(PointId id, F&& f) const {
    const PointId vertex = host_of(id);
    if (vertex != id) f(vertex);
    dt_.neighbors(vertex, scratch_neighbors_);
    for (const PointId w : scratch_neighbors_) {
      f(w);
      for (const PointId t : twins_of(w)) f(t);
    }
    for (const PointId t : twins_of(vertex))
      if (t != id) f(t);
  }
  /// The triangulation vertex that stands for id (id itself unless it is a twin).
  PointId host_of(PointId id) const { return twins_.host_of(id); }
  /// The twins that vertex stands for (empty unless it hosts some).
  const std::vector<PointId>& twins_of(PointId vertex) const { return twins_.twins_of(vertex); }

  /// Checks the triangulation at now() with exact predicates (every face positively
  /// oriented, every edge locally Delaunay, hull convex) and repairs what it finds.
  KineticAudit audit_and_repair();
  /// Combinatorial and geometric validity at now(), without repairing.
  bool is_valid() const;

  /// Tells `listener` (or nobody: nullptr, the default) of every edge solved from now on.
  /// The listener must outlive the engine or be unset first.
  void set_edge_listener(EdgeListener* listener) { edge_listener_ = listener; }

  const KineticStatistics& statistics() const { return stats_; }
  /// For an engine built to replace `earlier` (the same points renumbered): its counters
  /// go on from earlier's, the building itself not counted but as one renumbering; the
  /// queue figures are this engine's own (their maximum the larger of the two).
  void continue_statistics(const KineticStatistics& earlier);
  const KineticConfig& config() const { return config_; }
  const triangulation::DelaunayTriangulation& triangulation() const { return dt_; }
  /// Finite Delaunay edges at now() between triangulation vertices.
  std::vector<std::pair<PointId, PointId>> edges() const { return dt_.finite_edges(); }

 private:
  using Entry = EventQueue::Entry;
  /// Per-face record of what is scheduled for each of its edges (both faces of an
  /// edge hold the same record).
  struct FaceSchedule {
    std::array<double, 3> time{kNever, kNever, kNever};
    std::array<std::uint64_t, 3> seq{0, 0, 0};
    std::array<EventKind, 3> kind{EventKind::None, EventKind::None, EventKind::None};
    /// Bit i: the certificate of edge i is identically zero (see degenerate_faces_).
    std::uint8_t zero_certificate = 0;
  };

  void face_created(triangulation::FaceIndex f) override;
  void face_destroyed(triangulation::FaceIndex f) override;

  void set_now(double t);
  void execute(const Entry& e);
  void execute_failure(const Entry& e);
  void execute_approach(const Entry& e);
  /// Seconds from now until the finite ends of edge i of face f are closer than
  /// twin_release_distance_m while approaching: 0 when they already are, kNever when
  /// they never will be on their current motions (or an end is infinite).
  double approach_offset(triangulation::FaceIndex f, int i) const;
  void schedule_dirty_faces();
  /// Records whether edge i of f has an identically zero certificate.
  void watch_degenerate(triangulation::FaceIndex f, int i, bool zero_certificate);
  /// Flips the watched edges that the exact predicates find violated at now (Lawson).
  /// Returns true when it changed the triangulation.
  bool flip_degenerate_edges();
  void solve_edge(triangulation::FaceIndex f, int i, double from_offset, std::uint16_t retries);
  /// solve_edge with the edge's certificate at now already computed.
  void solve_edge(triangulation::FaceIndex f, int i, double from_offset, std::uint16_t retries,
                  const Polynomial& certificate);
  /// Certificate of edge i of f in time local to now: positive exactly while violated;
  /// the zero polynomial when it constrains nothing or is only rounding noise.
  Polynomial edge_certificate(triangulation::FaceIndex f, int i) const;
  double earliest_failure(triangulation::FaceIndex f) const;
  void clear_edge(triangulation::FaceIndex f, int i, bool count_discard);
  /// Queues an event of edge i of f at `time` (s) and records it on both faces of the edge.
  void schedule_edge(double time, triangulation::FaceIndex f, int i, EventKind kind, std::uint16_t retries);
  /// False for an entry descheduled since it was queued (its record holds another seq).
  bool is_live(const Entry& e) const;
  /// Clears every certificate around vertex and marks its faces dirty.
  void reschedule_star(PointId vertex);
  /// After vertex's velocity changed at now: an edge of its star whose renewal is still
  /// to come keeps it when renewal_still_holds; the others are cleared and solved again
  /// (design §2.3). Exact: up to that renewal no failure can happen on the new motion.
  void revalidate_star(PointId vertex);
  /// The new certificate of edge i of f is certainly negative (valid) until the renewal
  /// scheduled for the edge, and its ends come no closer than twin_release_distance_m.
  bool renewal_still_holds(triangulation::FaceIndex f, int i, const Polynomial& certificate) const;
  void tell_edge_listener(triangulation::FaceIndex f, int i);
  /// Removes id and attaches it again on trajectory `to` (at now).
  void reinsert(PointId id, const triangulation::Trajectory& to);
  /// advance() for the points' own operations, which sample the queue for queue_mean.
  void advance_sampled(double t);
  /// Keeps id's model if the report (p, v) at now stays within `allowed` of it for
  /// keep_model_s; then schedules the Drift deadline and returns true.
  bool keep_model(PointId id, Point2 p, Vector2 v, double deviation, double allowed);
  void cancel_drift(PointId id);
  void execute_drift(PointId id);
  /// Attaches id at its position now; `hint` is a face near it where the walk starts.
  void attach_point(PointId id, triangulation::FaceIndex hint = triangulation::kNoFace);
  /// An attached point next to id in the triangulation (its host for a twin), or
  /// kNoPoint: a start for locating id again after it moves a little.
  PointId attached_neighbour(PointId id) const;
  /// Detaches id, its faces dirty but not scheduled (callers schedule before time moves):
  /// a reinsertion attaches again at once, so the hole's faces it destroys are not solved
  /// (unless id hosted twins, whose attaching schedules them), half its certificates.
  void detach_point(PointId id);
  /// Detaches a triangulation vertex. Returns false when that took a full rebuild
  /// (counted in stats_.rebuilds), whose evictions are adopted.
  bool detach_vertex(PointId vertex);
  /// Retriangulates from scratch (the last-resort repair, counted in stats_.rebuilds)
  /// and adopts the evictions.
  void rebuild_triangulation();
  /// Makes each vertex a rebuild left detached a twin of the one at its position.
  void adopt_evictions(const std::vector<triangulation::Eviction>& evicted);
  /// Makes id (detached) a twin of host and schedules its release.
  void make_twin(PointId id, PointId host);
  /// Makes vertex (just detached) a twin of host, and its own twins follow it there.
  void merge_into(PointId vertex, PointId host);
  /// Queues the release of twin id for when it is twin_release_distance_m from its host.
  void schedule_twin_release(PointId id);
  void repair_around(const std::vector<PointId>& vertices);
  /// repair_around the four vertices of the quadrilateral of edge i of face f.
  void repair_quadrilateral(triangulation::FaceIndex f, int i);

  KineticConfig config_;
  double now_;
  triangulation::DelaunayTriangulation dt_;
  std::vector<FaceSchedule> schedule_;
  EventQueue queue_;
  std::vector<std::pair<triangulation::FaceIndex, std::uint32_t>> dirty_faces_;
  std::vector<std::uint32_t> dirty_mark_;
  /// Faces (with their generation) having an edge whose certificate is identically zero
  /// in floating point while the exact predicate on the rounded positions may still
  /// change sign at any instant: such edges are checked at the end of every advance().
  std::vector<std::pair<triangulation::FaceIndex, std::uint32_t>> degenerate_faces_;
  std::uint32_t dirty_round_ = 0;
  TwinRegistry twins_;
  std::vector<bool> live_;
  // By point: the latest report's trajectory while its model is kept, and the sequence
  // number of its Drift deadline (0: none scheduled).
  std::vector<triangulation::Trajectory> reported_;
  std::vector<std::uint64_t> drift_seq_;
  std::size_t live_points_ = 0;
  KineticStatistics stats_;
  EdgeListener* edge_listener_ = nullptr;
  mutable std::vector<PointId> scratch_neighbors_;
  std::vector<triangulation::FaceIndex> scratch_faces_;
  struct StarEdge {
    triangulation::FaceIndex face;
    int edge;
    Polynomial certificate;
  };
  std::vector<StarEdge> scratch_edges_;
};

}  // namespace kew::kinetic
