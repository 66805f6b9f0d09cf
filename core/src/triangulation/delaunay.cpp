#include "kew/triangulation/delaunay.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "kew/geometry/predicates.hpp"
#include "kew/util/gentle_growth.hpp"

namespace kew::triangulation {

using geometry::CircleSide;
using geometry::orient2d;
using geometry::Orientation;

namespace {
int orientation_sign(Point2 a, Point2 b, Point2 c) { return geometry::sign(orient2d(a, b, c)); }
/// True when p lies strictly between a and b on their common line (caller checked collinearity).
bool strictly_between(Point2 a, Point2 b, Point2 p) {
  // Exact for collinear doubles: compare along the dominant axis.
  if (a.x != b.x) return (a.x < p.x && p.x < b.x) || (b.x < p.x && p.x < a.x);
  return (a.y < p.y && p.y < b.y) || (b.y < p.y && p.y < a.y);
}
}  // namespace

DelaunayTriangulation::DelaunayTriangulation() {
  trajectories_.resize(1);
  cached_position_.resize(1);
  cached_epoch_.resize(1, 0);
}

void DelaunayTriangulation::set_time(double t) {
  if (t == time_) return;
  time_ = t;
  ++epoch_;
}

VertexIndex DelaunayTriangulation::create_vertex(const Trajectory& trajectory) {
  const VertexIndex v = tds_.create_vertex();
  if (v >= trajectories_.size()) {
    util::grow_to(trajectories_, v + 1);
    util::grow_to(cached_position_, v + 1);
    util::grow_to(cached_epoch_, v + 1, std::uint64_t{0});
  }
  trajectories_[v] = trajectory;
  cached_epoch_[v] = 0;
  return v;
}

void DelaunayTriangulation::destroy_vertex(VertexIndex v) { tds_.destroy_vertex(v); }

void DelaunayTriangulation::set_trajectory(VertexIndex v, const Trajectory& trajectory) {
  trajectories_[v] = trajectory;
  cached_epoch_[v] = 0;
}

Point2 DelaunayTriangulation::position(VertexIndex v) const {
  if (cached_epoch_[v] != epoch_) {
    cached_position_[v] = trajectories_[v].at(time_);
    cached_epoch_[v] = epoch_;
  }
  return cached_position_[v];
}

bool DelaunayTriangulation::is_pending(VertexIndex v) const {
  return std::find(pending_.begin(), pending_.end(), v) != pending_.end();
}

bool DelaunayTriangulation::is_flat() const {
  const FaceIndex f = tds_.vertex_face(kInfiniteVertex);
  if (f == kNoFace) return true;
  const Face& face = tds_.face(f);
  const int k = face.index_of(kInfiniteVertex);
  return tds_.face(face.neighbor[static_cast<unsigned>(k)]).is_infinite();
}

bool DelaunayTriangulation::collinear_with_chain(Point2 p) const {
  const Face& face = tds_.face(tds_.vertex_face(kInfiniteVertex));
  const int k = face.index_of(kInfiniteVertex);
  return orientation_sign(position(face.vertex[static_cast<unsigned>(ccw(k))]),
                          position(face.vertex[static_cast<unsigned>(cw(k))]), p) == 0;
}

bool DelaunayTriangulation::is_positive(FaceIndex f) const {
  const Face& face = tds_.face(f);
  if (face.is_infinite()) return true;
  return orientation_sign(position(face.vertex[0]), position(face.vertex[1]), position(face.vertex[2])) > 0;
}

EdgeState DelaunayTriangulation::edge_state(FaceIndex f, int i) const {
  const Face& face = tds_.face(f);
  const FaceIndex g = face.neighbor[static_cast<unsigned>(i)];
  const int j = tds_.mirror_index(f, i);
  const VertexIndex c = face.vertex[static_cast<unsigned>(i)];
  const VertexIndex a = face.vertex[static_cast<unsigned>(ccw(i))];
  const VertexIndex b = face.vertex[static_cast<unsigned>(cw(i))];
  const VertexIndex d = tds_.face(g).vertex[static_cast<unsigned>(j)];
  auto state = [](int s) { return static_cast<EdgeState>(s > 0 ? 1 : s < 0 ? -1 : 0); };
  if (a == kInfiniteVertex || b == kInfiniteVertex) {
    // An edge to the infinite vertex: the hull must turn left at its finite end x,
    // whose hull neighbours are c and d.
    const VertexIndex x = a == kInfiniteVertex ? b : a;
    if (c == d) return EdgeState::Valid;  // end of a flat chain: the hull turns back
    const Point2 px = position(x), pc = position(c), pd = position(d);
    const int s = a == kInfiniteVertex ? orientation_sign(px, pc, pd) : orientation_sign(px, pd, pc);
    if (s != 0) return state(s);
    // Collinear hull neighbours: valid only while x lies strictly between them.
    return strictly_between(pc, pd, px) ? EdgeState::Degenerate : EdgeState::Violated;
  }
  if (c == kInfiniteVertex && d == kInfiniteVertex) {
    // Both sides unbounded: a segment of a flat chain. Its order is certified at its ends.
    return EdgeState::Valid;
  }
  const Point2 pa = position(a), pb = position(b);
  if (d == kInfiniteVertex) return state(-orientation_sign(pa, pb, position(c)));
  if (c == kInfiniteVertex) return state(-orientation_sign(pb, pa, position(d)));
  return state(geometry::sign(geometry::incircle(pa, pb, position(c), position(d))));
}

bool DelaunayTriangulation::is_flippable(FaceIndex f, int i) const {
  const Face& face = tds_.face(f);
  const FaceIndex g = face.neighbor[static_cast<unsigned>(i)];
  if (g == f) return false;
  const int j = tds_.mirror_index(f, i);
  const VertexIndex c = face.vertex[static_cast<unsigned>(i)];
  const VertexIndex a = face.vertex[static_cast<unsigned>(ccw(i))];
  const VertexIndex b = face.vertex[static_cast<unsigned>(cw(i))];
  const VertexIndex d = tds_.face(g).vertex[static_cast<unsigned>(j)];
  if (c == kInfiniteVertex && d == kInfiniteVertex) return false;
  if (c == d) return false;
  // The flip makes (c, a, d) and (c, d, b); each must be infinite or strictly ccw.
  auto valid = [&](VertexIndex p, VertexIndex q, VertexIndex r) {
    if (p == kInfiniteVertex || q == kInfiniteVertex || r == kInfiniteVertex) return true;
    return orientation_sign(position(p), position(q), position(r)) > 0;
  };
  return valid(c, a, d) && valid(c, d, b);
}

bool DelaunayTriangulation::in_conflict(FaceIndex f, Point2 p) const {
  const Face& face = tds_.face(f);
  const int k = face.index_of(kInfiniteVertex);
  if (k < 0)
    return geometry::incircle(position(face.vertex[0]), position(face.vertex[1]), position(face.vertex[2]), p) ==
           CircleSide::Inside;
  const Point2 x = position(face.vertex[static_cast<unsigned>(ccw(k))]);
  const Point2 y = position(face.vertex[static_cast<unsigned>(cw(k))]);
  const int s = orientation_sign(x, y, p);
  return s > 0 || (s == 0 && strictly_between(x, y, p));
}

FaceIndex DelaunayTriangulation::locate(Point2 p, FaceIndex hint) const {
  FaceIndex f = hint;
  if (f == kNoFace || !tds_.face(f).alive) f = tds_.any_face();
  if (f == kNoFace) return kNoFace;
  if (is_flat()) {
    for (FaceIndex g = 0; g < tds_.face_capacity(); ++g)
      if (tds_.face(g).alive && in_conflict(g, p)) return g;
    return kNoFace;
  }
  if (tds_.face(f).is_infinite()) {
    const int k = tds_.face(f).index_of(kInfiniteVertex);
    f = tds_.face(f).neighbor[static_cast<unsigned>(k)];
  }
  // Remembering stochastic walk: never re-test the edge just crossed, and start the
  // edge tests at a pseudo-random index so the walk cannot cycle.
  FaceIndex previous = kNoFace;
  const std::size_t limit = 4 * tds_.face_capacity() + 64;
  for (std::size_t step = 0; step < limit; ++step) {
    const Face& face = tds_.face(f);
    if (face.is_infinite()) return f;
    walk_state_ ^= walk_state_ << 13;
    walk_state_ ^= walk_state_ >> 7;
    walk_state_ ^= walk_state_ << 17;
    const int start = static_cast<int>(walk_state_ % 3);
    bool moved = false;
    for (int m = 0; m < 3 && !moved; ++m) {
      const int i = (start + m) % 3;
      const FaceIndex g = face.neighbor[static_cast<unsigned>(i)];
      if (g == previous) continue;
      if (orientation_sign(position(face.vertex[static_cast<unsigned>(ccw(i))]),
                           position(face.vertex[static_cast<unsigned>(cw(i))]), p) < 0) {
        previous = f;
        f = g;
        moved = true;
      }
    }
    if (!moved) return f;
  }
  // The walk only fails to end on a broken triangulation; scan as a last resort.
  for (FaceIndex g = 0; g < tds_.face_capacity(); ++g)
    if (tds_.face(g).alive && in_conflict(g, p)) return g;
  return kNoFace;
}

AttachResult DelaunayTriangulation::attach(VertexIndex v, VertexIndex* same, FaceIndex hint) {
  const Point2 p = position(v);
  auto duplicate_of = [&](VertexIndex w) {
    if (same) *same = w;
    return AttachResult::Duplicate;
  };
  if (attached_ < 2) {
    for (VertexIndex w : pending_)
      if (position(w) == p) return duplicate_of(w);
    pending_.push_back(v);
    ++attached_;
    if (attached_ == 2) {
      const VertexIndex ends[2] = {pending_[0], pending_[1]};
      pending_.clear();
      tds_.make_chain(ends);
    }
    return AttachResult::Attached;
  }
  if (is_flat() && collinear_with_chain(p)) {
    // A point on the line of a flat chain: rebuild the chain in order.
    for (FaceIndex g = 0; g < tds_.face_capacity(); ++g) {
      const Face& face = tds_.face(g);
      if (!face.alive) continue;
      for (VertexIndex w : face.vertex)
        if (w != kInfiniteVertex && position(w) == p) return duplicate_of(w);
    }
    ++attached_;
    pending_.push_back(v);  // picked up by rebuild_flat
    rebuild_flat();
    return AttachResult::Attached;
  }
  const FaceIndex start = locate(p, hint);
  if (start == kNoFace || !in_conflict(start, p)) {
    // p sits on a vertex of the located face (the only way it is not in conflict).
    if (start != kNoFace)
      for (VertexIndex w : tds_.face(start).vertex)
        if (w != kInfiniteVertex && position(w) == p) return duplicate_of(w);
    return AttachResult::NotDelaunay;
  }
  // Bowyer–Watson: the conflict region is a connected set of faces around p.
  ++mark_;
  util::grow_to(face_mark_, tds_.face_capacity(), std::uint32_t{0});
  auto& region = scratch_faces_;
  auto& boundary = scratch_boundary_;
  region.clear();
  boundary.clear();
  region.push_back(start);
  face_mark_[start] = mark_;
  for (std::size_t k = 0; k < region.size(); ++k) {
    const FaceIndex f = region[k];
    const Face& face = tds_.face(f);
    for (VertexIndex w : face.vertex)
      if (w != kInfiniteVertex && position(w) == p) return duplicate_of(w);
    for (int i = 0; i < 3; ++i) {
      const FaceIndex g = face.neighbor[static_cast<unsigned>(i)];
      if (face_mark_[g] == mark_) continue;
      if (in_conflict(g, p)) {
        face_mark_[g] = mark_;
        region.push_back(g);
      }
    }
  }
  for (const FaceIndex f : region) {
    const Face& face = tds_.face(f);
    for (int i = 0; i < 3; ++i) {
      const FaceIndex g = face.neighbor[static_cast<unsigned>(i)];
      if (face_mark_[g] == mark_) continue;
      const VertexIndex from = face.vertex[static_cast<unsigned>(ccw(i))];
      const VertexIndex to = face.vertex[static_cast<unsigned>(cw(i))];
      // Star-shapedness: every new finite face (v, from, to) must be strictly ccw.
      if (from != kInfiniteVertex && to != kInfiniteVertex && orientation_sign(p, position(from), position(to)) <= 0)
        return AttachResult::NotDelaunay;
      boundary.push_back({from, to, g});
    }
  }
  auto& triangles = scratch_triangles_;
  triangles.clear();
  for (const BoundaryEdge& e : boundary) triangles.push_back({v, e.from, e.to});
  tds_.replace_faces(region, boundary, triangles);
  ++attached_;
  return AttachResult::Attached;
}

void DelaunayTriangulation::rebuild_flat() {
  // Collect the chain's vertices plus any newly pending one and order them along the line.
  std::vector<VertexIndex> vertices = vertices_in_faces(kInfiniteVertex);
  vertices.insert(vertices.end(), pending_.begin(), pending_.end());
  pending_.clear();
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  // Lexicographic order of collinear points is their order along the line.
  std::sort(vertices.begin(), vertices.end(), [&](VertexIndex x, VertexIndex y) {
    const Point2 px = position(x), py = position(y);
    return px.x < py.x || (px.x == py.x && px.y < py.y);
  });
  tds_.clear_faces();
  if (vertices.size() >= 2) {
    tds_.make_chain(vertices);
  } else {
    pending_ = vertices;
  }
}

bool DelaunayTriangulation::triangulate_hole(std::vector<VertexIndex>& polygon,
                                             std::vector<std::array<VertexIndex, 3>>& out) const {
  const std::size_t k = polygon.size();
  if (k < 3) return false;
  if (k == 3) {
    if (polygon[0] != kInfiniteVertex && polygon[1] != kInfiniteVertex && polygon[2] != kInfiniteVertex &&
        orientation_sign(position(polygon[0]), position(polygon[1]), position(polygon[2])) <= 0)
      return false;
    out.push_back({polygon[0], polygon[1], polygon[2]});
    return true;
  }
  // Base edge with two finite ends; the hole lies on its left.
  std::size_t s = 0;
  while (s < k && (polygon[s] == kInfiniteVertex || polygon[(s + 1) % k] == kInfiniteVertex)) ++s;
  if (s == k) return false;
  std::rotate(polygon.begin(), polygon.begin() + static_cast<std::ptrdiff_t>(s), polygon.end());
  const Point2 a = position(polygon[0]);
  const Point2 b = position(polygon[1]);
  std::size_t best = 0;
  for (std::size_t m = 2; m < k; ++m) {
    const VertexIndex x = polygon[m];
    if (x != kInfiniteVertex && orientation_sign(a, b, position(x)) <= 0) continue;
    if (best == 0) {
      best = m;
      continue;
    }
    const VertexIndex current = polygon[best];
    bool inside;
    if (x == kInfiniteVertex) {
      inside = false;  // never inside the circle of a ccw finite triangle
    } else if (current == kInfiniteVertex) {
      inside = true;  // a finite candidate on the left is inside the half-plane "circle"
    } else {
      inside = geometry::incircle(a, b, position(current), position(x)) == CircleSide::Inside;
    }
    if (inside) best = m;
  }
  if (best == 0) return false;
  out.push_back({polygon[0], polygon[1], polygon[best]});
  std::vector<VertexIndex> right(polygon.begin() + 1, polygon.begin() + static_cast<std::ptrdiff_t>(best) + 1);
  std::vector<VertexIndex> left(polygon.begin() + static_cast<std::ptrdiff_t>(best), polygon.end());
  left.push_back(polygon[0]);
  if (right.size() >= 3 && !triangulate_hole(right, out)) return false;
  if (left.size() >= 3 && !triangulate_hole(left, out)) return false;
  return true;
}

DetachResult DelaunayTriangulation::detach(VertexIndex v) {
  if (is_pending(v)) {
    pending_.erase(std::find(pending_.begin(), pending_.end(), v));
    --attached_;
    return {};
  }
  assert(tds_.is_attached(v));
  --attached_;
  if (attached_ < 2) {
    // One point left: no face can exist; keep it pending.
    pending_ = vertices_in_faces(v);
    tds_.clear_faces();
    return {};
  }
  if (is_flat()) {
    // Remove v from the chain and rebuild it.
    pending_ = vertices_in_faces(v);
    tds_.clear_faces();
    rebuild_flat();
    return {};
  }
  auto& star = scratch_faces_;
  tds_.incident_faces(v, star);
  auto& boundary = scratch_boundary_;
  boundary.clear();
  std::vector<VertexIndex> polygon;
  polygon.reserve(star.size());
  for (FaceIndex f : star) {
    const Face& face = tds_.face(f);
    const int i = face.index_of(v);
    const VertexIndex from = face.vertex[static_cast<unsigned>(ccw(i))];
    const VertexIndex to = face.vertex[static_cast<unsigned>(cw(i))];
    boundary.push_back({from, to, face.neighbor[static_cast<unsigned>(i)]});
    polygon.push_back(from);
  }
  auto& triangles = scratch_triangles_;
  triangles.clear();
  // A vertex repeated on the link means a degenerate neighbourhood: let the caller rebuild.
  std::vector<VertexIndex> sorted = polygon;
  std::sort(sorted.begin(), sorted.end());
  const bool simple_link = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
  if (!simple_link || !triangulate_hole(polygon, triangles)) return {false, rebuild_without(v)};
  const std::vector<FaceIndex> region = star;
  const std::vector<BoundaryEdge> edges = boundary;
  tds_.replace_faces(region, edges, triangles);
  return {};
}

std::vector<VertexIndex> DelaunayTriangulation::vertices_in_faces(VertexIndex except) const {
  std::vector<VertexIndex> vertices;
  for (FaceIndex g = 0; g < tds_.face_capacity(); ++g) {
    const Face& face = tds_.face(g);
    if (!face.alive) continue;
    for (VertexIndex w : face.vertex)
      if (w != kInfiniteVertex && w != except) vertices.push_back(w);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

std::vector<Eviction> DelaunayTriangulation::rebuild_without(VertexIndex v) {
  std::vector<VertexIndex> rest = vertices_in_faces(v);
  for (VertexIndex w : pending_)
    if (w != v) rest.push_back(w);
  tds_.clear_faces();
  pending_.clear();
  attached_ = 0;
  return insert_all(std::move(rest));
}

std::vector<Eviction> DelaunayTriangulation::rebuild() { return rebuild_without(kInfiniteVertex); }

std::vector<Eviction> DelaunayTriangulation::insert_all(std::vector<VertexIndex> vertices) {
  // Insert in a spatially coherent order (Morton order of a grid over the bounding box)
  // so each walk starts next to its target.
  double min_x = INFINITY, min_y = INFINITY, max_x = -INFINITY, max_y = -INFINITY;
  for (VertexIndex w : vertices) {
    const Point2 p = position(w);
    min_x = std::min(min_x, p.x);
    min_y = std::min(min_y, p.y);
    max_x = std::max(max_x, p.x);
    max_y = std::max(max_y, p.y);
  }
  const double span = std::max({max_x - min_x, max_y - min_y, 1e-300});
  auto morton = [&](VertexIndex w) {
    const Point2 p = position(w);
    const auto qx = static_cast<std::uint32_t>((p.x - min_x) / span * 65535.0);
    const auto qy = static_cast<std::uint32_t>((p.y - min_y) / span * 65535.0);
    std::uint64_t code = 0;
    for (int bit = 0; bit < 16; ++bit)
      code |= (std::uint64_t{(qx >> bit) & 1u} << (2 * bit)) | (std::uint64_t{(qy >> bit) & 1u} << (2 * bit + 1));
    return code;
  };
  std::vector<std::pair<std::uint64_t, VertexIndex>> order;
  order.reserve(vertices.size());
  for (VertexIndex w : vertices) order.emplace_back(morton(w), w);
  std::sort(order.begin(), order.end());
  std::vector<Eviction> evicted;
  FaceIndex hint = kNoFace;
  for (const auto& [code, w] : order) {
    VertexIndex same = kNoVertex;
    const AttachResult r = attach(w, &same, hint);
    if (r == AttachResult::Duplicate) {
      evicted.push_back({w, same});
    } else if (r == AttachResult::Attached) {
      hint = tds_.vertex_face(w);
    } else {
      assert(false && "insertion into a fresh Delaunay triangulation cannot fail");
    }
  }
  return evicted;
}

std::size_t DelaunayTriangulation::make_locally_delaunay(std::vector<std::pair<FaceIndex, int>>& seeds,
                                                         std::vector<std::pair<FaceIndex, int>>* stuck) {
  std::size_t flips = 0;
  std::size_t guard = 0;
  const std::size_t limit = 64 * (tds_.face_capacity() + 16);
  while (!seeds.empty() && guard++ < limit) {
    const auto [f, i] = seeds.back();
    seeds.pop_back();
    if (!tds_.face(f).alive) continue;
    if (edge_state(f, i) != EdgeState::Violated) continue;
    if (!is_flippable(f, i)) {
      if (stuck) stuck->emplace_back(f, i);
      continue;
    }
    const auto [p, q] = tds_.flip(f, i);
    ++flips;
    // The four outer edges of the new quadrilateral may now be violated.
    seeds.emplace_back(p, 0);
    seeds.emplace_back(p, 2);
    seeds.emplace_back(q, 0);
    seeds.emplace_back(q, 1);
  }
  return flips;
}

AuditReport DelaunayTriangulation::audit() const {
  AuditReport report;
  report.combinatorially_valid = tds_.is_valid();
  if (!report.combinatorially_valid) return report;
  for (FaceIndex f = 0; f < tds_.face_capacity(); ++f) {
    const Face& face = tds_.face(f);
    if (!face.alive) continue;
    ++report.faces_checked;
    if (!is_positive(f)) ++report.inverted_faces;
    for (int i = 0; i < 3; ++i) {
      if (face.neighbor[static_cast<unsigned>(i)] < f) continue;  // each edge once (by its larger face)
      ++report.edges_checked;
      if (edge_state(f, i) == EdgeState::Violated) ++report.non_delaunay_edges;
    }
  }
  return report;
}

void DelaunayTriangulation::neighbors(VertexIndex v, std::vector<VertexIndex>& out) const {
  out.clear();
  if (is_pending(v)) {
    for (VertexIndex w : pending_)
      if (w != v) out.push_back(w);
    return;
  }
  tds_.adjacent_vertices(v, out);
  out.erase(std::remove(out.begin(), out.end(), kInfiniteVertex), out.end());
  // A flat chain's end vertex sees its single neighbour twice.
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

std::vector<std::pair<VertexIndex, VertexIndex>> DelaunayTriangulation::finite_edges() const {
  std::vector<std::pair<VertexIndex, VertexIndex>> edges;
  for (FaceIndex f = 0; f < tds_.face_capacity(); ++f) {
    const Face& face = tds_.face(f);
    if (!face.alive) continue;
    for (int i = 0; i < 3; ++i) {
      const VertexIndex a = face.vertex[static_cast<unsigned>(ccw(i))];
      const VertexIndex b = face.vertex[static_cast<unsigned>(cw(i))];
      if (a == kInfiniteVertex || b == kInfiniteVertex) continue;
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace kew::triangulation
