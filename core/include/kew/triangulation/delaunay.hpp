#pragma once
// Delaunay triangulation of moving points, evaluated at one instant: the geometry
// (points, predicates, conflict regions) on top of the combinatorial Tds. Points move
// linearly; every predicate is exact on the doubles that position() returns at the
// current time, so "Delaunay" always means Delaunay for exactly those positions.

#include <cstdint>
#include <vector>

#include "kew/geometry/vector2.hpp"
#include "kew/triangulation/tds.hpp"

namespace kew::triangulation {

using geometry::Point2;
using geometry::Vector2;

/// Linear motion: position(t) = origin + velocity · (t − t0). Metres, m/s, seconds.
struct Trajectory {
  Point2 origin;
  Vector2 velocity;
  double t0 = 0.0;
  Point2 at(double t) const { return origin + (t - t0) * velocity; }
};

/// What an edge's certificate says at the current time.
enum class EdgeState : signed char {
  Valid = -1,       // locally Delaunay (or a hull edge that is convex)
  Degenerate = 0,   // on the boundary: cocircular, or collinear hull vertices
  Violated = 1,     // not locally Delaunay / hull not convex / collinear order broken
};

/// Defects an audit can find, each counted separately.
struct AuditReport {
  std::size_t faces_checked = 0;
  std::size_t edges_checked = 0;
  std::size_t inverted_faces = 0;      // finite face not strictly counter-clockwise
  std::size_t non_delaunay_edges = 0;  // EdgeState::Violated
  bool combinatorially_valid = true;
  std::size_t violations() const { return inverted_faces + non_delaunay_edges + (combinatorially_valid ? 0 : 1); }
};

/// Outcome of attaching a point.
enum class AttachResult { Attached, Duplicate, NotDelaunay };

/// A vertex that a rebuild found at exactly the position of another and left detached.
struct Eviction {
  VertexIndex vertex;  ///< left detached
  VertexIndex same;    ///< the attached vertex at its position
};

/// What detach() did.
struct DetachResult {
  /// False when the hole could not be triangulated validly (a degenerate neighbourhood)
  /// and every other vertex was inserted again from scratch, as by rebuild().
  bool hole_triangulated = true;
  /// What that rebuild evicted, in insertion order; empty when the hole was triangulated.
  std::vector<Eviction> evicted;
};

class DelaunayTriangulation {
 public:
  DelaunayTriangulation();

  Tds& tds() { return tds_; }
  const Tds& tds() const { return tds_; }

  /// Moves the instant at which positions and predicates are evaluated (seconds).
  void set_time(double t);
  double time() const { return time_; }

  /// A new, detached vertex following `trajectory`.
  VertexIndex create_vertex(const Trajectory& trajectory);
  /// Releases a detached vertex.
  void destroy_vertex(VertexIndex v);
  const Trajectory& trajectory(VertexIndex v) const { return trajectories_[v]; }
  /// Changes a vertex's motion. A caller that changes the position at time() of an
  /// attached vertex is responsible for repairing the triangulation.
  void set_trajectory(VertexIndex v, const Trajectory& trajectory);
  /// Position at time(); exact predicates are applied to exactly these doubles.
  Point2 position(VertexIndex v) const;

  /// Number of vertices in the triangulation (attached), excluding the infinite one.
  std::size_t size() const { return attached_; }
  bool is_attached(VertexIndex v) const { return tds_.is_attached(v) || is_pending(v); }

  /// Inserts a detached vertex at its position at time(). On Duplicate, `*same` is the
  /// attached vertex at exactly that position and v stays detached. NotDelaunay means
  /// the conflict region was not star-shaped (the triangulation needs repair first).
  AttachResult attach(VertexIndex v, VertexIndex* same = nullptr, FaceIndex hint = kNoFace);
  /// Removes an attached vertex and retriangulates its hole, or, when the hole cannot
  /// be triangulated validly, the whole triangulation. The vertex ends detached either
  /// way; the vertices the rebuild evicts are the caller's to account for.
  [[nodiscard]] DetachResult detach(VertexIndex v);
  /// Retriangulates every attached vertex from scratch at time(). Returns the vertices
  /// found at exactly the position of one inserted before them, in insertion order: they
  /// are left detached, for the caller to account for.
  [[nodiscard]] std::vector<Eviction> rebuild();

  /// State of the edge opposite vertex i of face f at time().
  EdgeState edge_state(FaceIndex f, int i) const;
  /// True when flipping that edge yields two valid faces at time().
  bool is_flippable(FaceIndex f, int i) const;
  /// True for infinite faces and strictly counter-clockwise finite faces.
  bool is_positive(FaceIndex f) const;
  /// True when no finite face exists (all attached points collinear, or fewer than 3).
  bool is_flat() const;

  /// Flips violated edges reachable from `seeds` (face, index pairs) until all are
  /// locally Delaunay (Lawson). Returns the number of flips; edges that are violated
  /// but cannot be flipped are appended to `stuck`.
  std::size_t make_locally_delaunay(std::vector<std::pair<FaceIndex, int>>& seeds,
                                    std::vector<std::pair<FaceIndex, int>>* stuck = nullptr);

  /// Exact check of every face and edge at time(). O(n).
  AuditReport audit() const;
  bool is_valid() const { return audit().violations() == 0; }

  /// Face of the triangulation containing p, or one in conflict with p (outside the hull).
  FaceIndex locate(Point2 p, FaceIndex hint = kNoFace) const;

  /// Attached vertices adjacent to v (finite ones only).
  void neighbors(VertexIndex v, std::vector<VertexIndex>& out) const;
  /// Every finite edge once, as (smaller, larger) vertex index pairs.
  std::vector<std::pair<VertexIndex, VertexIndex>> finite_edges() const;

 private:
  bool is_pending(VertexIndex v) const;
  bool collinear_with_chain(Point2 p) const;
  bool in_conflict(FaceIndex f, Point2 p) const;
  void rebuild_flat();
  /// Every finite vertex of a live face but `except`, sorted, once each.
  std::vector<VertexIndex> vertices_in_faces(VertexIndex except) const;
  /// Retriangulates every attached vertex but v from scratch; returns the evictions.
  std::vector<Eviction> rebuild_without(VertexIndex v);
  /// Attaches the (detached) vertices; returns those found at another one's position.
  std::vector<Eviction> insert_all(std::vector<VertexIndex> vertices);
  bool triangulate_hole(std::vector<VertexIndex>& polygon, std::vector<std::array<VertexIndex, 3>>& out) const;

  Tds tds_;
  double time_ = 0.0;
  std::uint64_t epoch_ = 1;
  std::vector<Trajectory> trajectories_;
  mutable std::vector<Point2> cached_position_;
  mutable std::vector<std::uint64_t> cached_epoch_;
  /// Attached vertices while fewer than two exist (no faces can be formed yet).
  std::vector<VertexIndex> pending_;
  std::size_t attached_ = 0;
  mutable std::uint64_t walk_state_ = 0x9E3779B97F4A7C15ull;

  // Scratch buffers reused across calls to keep the hot paths allocation-free.
  mutable std::vector<FaceIndex> scratch_faces_;
  mutable std::vector<BoundaryEdge> scratch_boundary_;
  mutable std::vector<std::array<VertexIndex, 3>> scratch_triangles_;
  mutable std::vector<std::uint32_t> face_mark_;
  mutable std::uint32_t mark_ = 0;
};

}  // namespace kew::triangulation
