#pragma once
// Which points of the kinetic engine are twins of which (design §7.3). A twin is a point
// kept out of the triangulation because it is too close to a vertex, its host, which
// stands for it there. This class is the combinatorial half only, as CGAL keeps
// combinatorics apart from geometry: when points become twins and when they part is the
// engine's business; the registry keeps the links from twins to hosts and back in
// agreement, and remembers which queued event releases each twin.

#include <cstdint>
#include <span>
#include <vector>

#include "kew/triangulation/tds.hpp"

namespace kew::kinetic {

/// A point of the kinetic engine, numbered as the triangulation vertex made for it.
using PointId = triangulation::VertexIndex;
inline constexpr PointId kNoPoint = triangulation::kNoVertex;

class TwinRegistry {
 public:
  /// Registers id, a new point or one whose number is reused, as a point of its own: no
  /// host, no twins, no release queued. Every other call takes registered ids only.
  void add(PointId id);

  bool is_twin(PointId id) const { return twin_host_[id] != kNoPoint; }
  /// The vertex that stands for id: its host for a twin, id itself otherwise.
  PointId host_of(PointId id) const { return is_twin(id) ? twin_host_[id] : id; }
  /// The twins of vertex, in the order they became twins of it; empty for a twin, for a
  /// point without twins and for any id never registered.
  const std::vector<PointId>& twins_of(PointId vertex) const {
    return vertex < twins_.size() ? twins_[vertex] : no_twins_;
  }

  /// Makes id, a point of its own without twins, a twin of host_of(host) (≠ id).
  void make_twin(PointId id, PointId host);
  /// Makes the twin id a point of its own again; its release is forgotten.
  void unlink(PointId id);
  /// Makes every twin of vertex a point of its own again (their releases forgotten) and
  /// returns them in the order they became twins, which is the order to reattach them in.
  [[nodiscard]] std::vector<PointId> release_all(PointId vertex);
  /// Makes vertex, a point of its own that just left the triangulation, a twin of
  /// host_of(host) (≠ vertex); its own twins follow it to that host. Returns the points
  /// that changed host, vertex first, each of them needing a new release; the span stays
  /// valid until a link next changes (set_release_seq changes none).
  std::span<const PointId> merge_into(PointId vertex, PointId host);

  /// Sequence number (EventQueue::push) of the queued release of twin id; 0 when none is.
  std::uint64_t release_seq(PointId id) const { return release_seq_[id]; }
  /// Records the release queued for twin id; 0: none is queued (any earlier one is stale).
  void set_release_seq(PointId id, std::uint64_t seq) { release_seq_[id] = seq; }

  /// The links agree both ways (a twin is listed once, by its host, and lists no twins
  /// of its own), no host is a twin, and only twins have a release queued. O(points +
  /// twins · twins per host).
  bool is_valid() const;

 private:
  std::vector<PointId> twin_host_;           // kNoPoint: not a twin
  std::vector<std::vector<PointId>> twins_;  // by host
  std::vector<PointId> no_twins_;            // always empty: twins_of() for unregistered ids
  std::vector<std::uint64_t> release_seq_;
};

}  // namespace kew::kinetic
