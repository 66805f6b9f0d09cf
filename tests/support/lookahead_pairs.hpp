#pragma once
// Kinetic detection (design §2.7): the prototype. It keeps H, the pairs
// of tracks that may come within the horizontal minimum during the look-ahead window,
// as a set changed by kinetic events instead of searched for at every update, so that an
// update of track i tests H(i) only.
//
// Each track has a *model*, a straight-line trajectory kept while every report stays
// within `tolerance_m` of it over the whole look-ahead (position and velocity error
// together), and H is exact for the models with the minimum widened by twice that
// tolerance: every pair whose reported trajectories come within `separation_m` in
// [t, t + T] is in H. For a pair of models with relative position d(u), H holds it while
// the window [t, t + T] overlaps {u : |d(u)| < S'}: from the moment its look-ahead
// points q = p + v·T come within S' (entry) to the moment its positions separate beyond
// S' (exit). Entries are found by a kinetic Delaunay triangulation of the q-points
// (kinetic::KineticDelaunay, told of every edge it solves): when a pair's q-points come
// within S', either they are a Delaunay edge or a third point k lies in the disk on
// their diameter, within S' of both, so (i, k) and (k, j) are already in H (the Gabriel
// gap, closed by scheduling the entry of every such two-hop pair when its second half
// enters H). Exits are closed-form. A model replaced (a report beyond the tolerance, a
// kept report that runs out, a new track) removes the track's pairs and finds its
// current ones with the exact disk search of design §2.1 on the q-points.
//
// Twins of the triangulation (q-points within a millimetre) are not vertices and have no
// edges; a twin is in H with its host, so the closure of its host's pairs reaches it, and
// the metre of margin in S' covers the millimetre (design §2.7). As a safeguard every
// query also tests the twins directly, and a twin's own query searches the disk.
//
// Straight-line prediction only: the turn hypothesis of design §4.4 is not covered.
// A prototype for measurement (tests/bench/peers/lookahead.cpp, kew_peers_bench's method
// kew-lookahead) and the property test that proves it exact
// (tests/core/property/test_lookahead_pairs.cpp).

#include <cstdint>
#include <map>
#include <queue>
#include <vector>

#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/probe/proximity_search.hpp"

namespace kew::testing {

struct LookaheadPairsConfig {
  /// S (m, > 0): the largest horizontal minimum of any pair (S_h times the largest
  /// projection scale).
  double separation_m = 9260.0;
  /// T (s, ≥ 0): the look-ahead.
  double lookahead_s = 120.0;
  /// ε (m, ≥ 0): how far a report may stray from its track's model, anywhere in the
  /// look-ahead, before the model is replaced. H is kept at S' = S + 2ε.
  double tolerance_m = 1000.0;
  /// K (s, > 0): how long a kept report's bound is vouched for; a track that reports
  /// nothing newer by then gets the report as its model (a Drift).
  double keep_s = 10.0;
  /// v_max (m/s, > 0): a bound on every reported speed (the disk search's radius).
  double max_speed_mps = 400.0;
  /// The q-triangulation's threshold and lazy window; its tolerance and kept models are
  /// not used (the models here are kept by LookaheadPairs itself).
  kinetic::KineticConfig kinetic;
};

struct LookaheadPairsStatistics {
  std::uint64_t reports = 0;
  std::uint64_t kept = 0;          ///< reports within ε of the model
  std::uint64_t replaced = 0;      ///< reports beyond it, and new tracks
  std::uint64_t drifts = 0;        ///< kept reports that became models at their deadline
  std::uint64_t disk_searches = 0; ///< model replacements, twin releases, twins' queries
  std::uint64_t edges_told = 0;    ///< edges the q-triangulation solved
  std::uint64_t entries = 0;       ///< pairs entering H
  std::uint64_t exits = 0;
  std::uint64_t two_hop_considered = 0;  ///< candidate pairs computed (edges, two hops, disks)
  std::uint64_t two_hop_pruned = 0;      ///< two-hop entries after their witness leaves: not queued
  std::uint64_t entries_queued = 0;   ///< future entries queued
  std::uint64_t events_stale = 0;  ///< queued entries, exits and drifts dropped unused
  std::size_t queue_max = 0;
};

class LookaheadPairs final : private kinetic::EdgeListener {
 public:
  using Key = std::uint32_t;  ///< the caller's name for a track (a slot)

  /// `start_time` (s) on the epoch every later time uses.
  explicit LookaheadPairs(const LookaheadPairsConfig& config, double start_time = 0.0);
  LookaheadPairs(const LookaheadPairs&) = delete;
  LookaheadPairs& operator=(const LookaheadPairs&) = delete;

  /// Processes everything up to t (s, ≥ now()).
  void advance(double t);
  double now() const { return kdt_.now(); }

  /// Track `key` reported at t (≥ now()) at position p (m) with velocity v (m/s,
  /// |v| ≤ max_speed_mps), moving on in a straight line. A new key starts a track.
  void report(Key key, double t, geometry::Point2 p, geometry::Vector2 v);
  /// Track `key` leaves at t (≥ now()); unknown keys are ignored.
  void remove(Key key, double t);

  /// Calls f(other) for every track other than `key` whose reported trajectory may come
  /// within separation_m of key's during [now(), now() + T] (a superset: H(key) and the
  /// twins). Each other track at most once.
  template <class F>
  void for_each_candidate(Key key, F&& f) {
    const PointId id = point_of_[key];
    if (kdt_.host_of(id) != id) {
      search_disk(id);
      for (const PointId j : found_) f(key_of_[j]);
      return;
    }
    for (const Partner& j : partners_[id]) f(key_of_[j.id]);
    for (const PointId t : twins_)
      if (t != id && !holds(id, t)) f(key_of_[t]);
  }

  /// True when H holds every current pair of models (both vertices) that the definition
  /// puts in it, and the q-triangulation is valid. O(n²): tests only.
  bool is_valid() const;

  const LookaheadPairsStatistics& statistics() const { return stats_; }
  /// When (s) a report of `key` last replaced its model, or −∞ if none has since its
  /// first report (or the key is unknown): how recently a track turned or jumped
  /// (kew_peers_bench).
  double last_replaced(Key key) const;
  const kinetic::KineticStatistics& triangulation_statistics() const { return kdt_.statistics(); }
  /// Σ |H(i)| over the tracks (each pair twice).
  std::size_t pair_ends() const;

 private:
  using PointId = kinetic::PointId;
  enum class Kind : std::uint8_t { Entry, Exit, Drift };
  struct Event {
    double time;
    std::uint64_t seq;
    PointId a, b;  // b unused for Drift
    std::uint32_t version_a, version_b;
    Kind kind;
    bool operator>(const Event& o) const { return time != o.time ? time > o.time : seq > o.seq; }
  };
  struct Interval {
    double begin, end;  // absolute times; empty unless begin < end
  };
  struct Partner {
    PointId id;
    double exit;  // when the pair leaves H on the current models (s)
  };
  struct Report {
    geometry::Point2 p;  // at t
    geometry::Vector2 v;
    double t = 0.0;
  };

  void edge_solved(PointId a, PointId b) override;
  /// The times during which the models of a and b put the pair in H.
  Interval membership(PointId a, PointId b) const;
  geometry::Point2 model_position(PointId id) const;  // p at kdt_.now()
  bool holds(PointId a, PointId b) const;
  /// Versions are odd while the point is live and grow at each model change.
  bool live(PointId id) const { return id < version_.size() && version_[id] % 2 == 1; }
  void push(double time, Kind kind, PointId a, PointId b);
  void process_until(double t);
  void run_event(const Event& e);
  /// Puts the pair in H with its exit queued; false when it was there already.
  bool add_pair(PointId a, PointId b, double exit);
  /// Adds the pair at logical time `at` and closes H under two hops from it.
  void enter(PointId a, PointId b, double at);
  /// Enters the pairs consider() found in H at `at`, and those their closure finds.
  void enter_waiting(double at);
  /// A pair that may enter H (an edge, a two-hop pair, a disk search's find), at `at`;
  /// an entry at or after `before` is not queued (the two-hop witness has left by then).
  void consider(PointId a, PointId b, double at, double before = kinetic::kNever);
  void forget_pairs(PointId id);
  void drop_partner(PointId from, PointId partner);
  /// Gives id the model `to` (at now()) and finds its current pairs.
  void replace_model(PointId id, geometry::Point2 p, geometry::Vector2 v);
  void search_disk(PointId id);
  void find_pairs(PointId id);
  /// After each engine call: twins made (tested directly from now on) and released
  /// (their pairs found again).
  void sync_twins();

  LookaheadPairsConfig config_;
  double widened_;  // S'
  kinetic::KineticDelaunay kdt_;
  probe::ProximitySearch search_;
  std::vector<PointId> point_of_;  // by key
  std::vector<Key> key_of_;        // by point
  std::vector<std::uint32_t> version_;
  std::vector<std::vector<Partner>> partners_;
  std::vector<Report> pending_;
  std::vector<std::uint64_t> drift_seq_;
  std::vector<std::uint8_t> is_twin_;
  std::vector<double> replaced_at_;  // by point: last replacement by a report
  std::vector<PointId> twins_;
  std::uint64_t twin_changes_seen_ = 0;
  // Events before near_end_ wait in a heap; later ones in buckets of kBucket_s seconds,
  // moved into the heap when the clock reaches their bucket.
  static constexpr double kBucket_s = 8.0;
  static std::int64_t bucket_of(double time);
  bool current(const Event& e) const;  // its points' models are those it was computed on
  void refill(double t);               // every bucket starting at or before t into the heap
  std::priority_queue<Event, std::vector<Event>, std::greater<>> queue_;
  double near_end_;
  std::map<std::int64_t, std::vector<Event>> far_;
  std::size_t far_size_ = 0;
  std::uint64_t next_seq_ = 1;
  struct Waiting {
    PointId a, b;
    double exit;
  };
  std::vector<Waiting> work_;  // pairs to enter at the current time
  std::vector<PointId> found_;
  std::vector<std::uint32_t> mark_;  // by point: reached in find_pairs() round mark_round_
  std::uint32_t mark_round_ = 0;
  PointId replacing_ = kinetic::kNoPoint;  // whose model update() is changing
  LookaheadPairsStatistics stats_;
};

}  // namespace kew::testing
