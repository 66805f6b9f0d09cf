#include "kew/triangulation/tds.hpp"

#include <algorithm>
#include <cassert>

#include "kew/util/gentle_growth.hpp"

namespace kew::triangulation {

Tds::Tds() {
  // Vertex 0 is the infinite vertex; it lives as long as the structure.
  vertex_face_.push_back(kNoFace);
  vertex_alive_.push_back(true);
}

VertexIndex Tds::create_vertex() {
  if (!free_vertices_.empty()) {
    const VertexIndex v = free_vertices_.back();
    free_vertices_.pop_back();
    vertex_alive_[v] = true;
    vertex_face_[v] = kNoFace;
    return v;
  }
  util::push_back_gently(vertex_face_, kNoFace);
  vertex_alive_.push_back(true);
  return static_cast<VertexIndex>(vertex_face_.size() - 1);
}

void Tds::destroy_vertex(VertexIndex v) {
  assert(v != kInfiniteVertex && vertex_alive(v) && vertex_face_[v] == kNoFace);
  vertex_alive_[v] = false;
  free_vertices_.push_back(v);
}

FaceIndex Tds::any_face() const {
  const FaceIndex f = vertex_face_[kInfiniteVertex];
  return f;
}

FaceIndex Tds::create_face(VertexIndex a, VertexIndex b, VertexIndex c) {
  FaceIndex f;
  if (!free_faces_.empty()) {
    f = free_faces_.back();
    free_faces_.pop_back();
  } else {
    util::push_back_gently(faces_, Face{});
    f = static_cast<FaceIndex>(faces_.size() - 1);
  }
  Face& face = faces_[f];
  face.vertex = {a, b, c};
  face.neighbor = {kNoFace, kNoFace, kNoFace};
  face.alive = true;
  ++live_faces_;
  for (VertexIndex v : face.vertex) vertex_face_[v] = f;
  return f;
}

void Tds::destroy_face(FaceIndex f) {
  Face& face = faces_[f];
  assert(face.alive);
  if (observer_) observer_->face_destroyed(f);
  face.alive = false;
  ++face.generation;
  --live_faces_;
  free_faces_.push_back(f);
}

void Tds::link(FaceIndex f, int i, FaceIndex g, int j) {
  faces_[f].neighbor[static_cast<unsigned>(i)] = g;
  faces_[g].neighbor[static_cast<unsigned>(j)] = f;
}

int Tds::mirror_index(FaceIndex f, int i) const {
  const Face& a = faces_[f];
  const Face& b = faces_[a.neighbor[static_cast<unsigned>(i)]];
  const VertexIndex from = a.vertex[static_cast<unsigned>(ccw(i))];
  const VertexIndex to = a.vertex[static_cast<unsigned>(cw(i))];
  for (int j = 0; j < 3; ++j)
    if (b.vertex[static_cast<unsigned>(ccw(j))] == to && b.vertex[static_cast<unsigned>(cw(j))] == from) return j;
  assert(false && "neighbour does not share the edge");
  return -1;
}

void Tds::relink_outside(FaceIndex outside, VertexIndex a, VertexIndex b, FaceIndex inside, int inside_index) {
  // The outside face sees the edge as b→a (opposite direction).
  Face& o = faces_[outside];
  for (int j = 0; j < 3; ++j) {
    if (o.vertex[static_cast<unsigned>(ccw(j))] == b && o.vertex[static_cast<unsigned>(cw(j))] == a) {
      link(inside, inside_index, outside, j);
      return;
    }
  }
  assert(false && "outside face does not contain the boundary edge");
}

void Tds::make_chain(std::span<const VertexIndex> ordered) {
  assert(live_faces_ == 0 && ordered.size() >= 2);
  const std::size_t segments = ordered.size() - 1;
  std::vector<FaceIndex> side_a(segments), side_b(segments);
  for (std::size_t s = 0; s < segments; ++s) {
    side_a[s] = create_face(ordered[s + 1], ordered[s], kInfiniteVertex);
    side_b[s] = create_face(ordered[s], ordered[s + 1], kInfiniteVertex);
  }
  for (std::size_t s = 0; s < segments; ++s) {
    const bool first = s == 0;
    const bool last = s + 1 == segments;
    Face& a = faces_[side_a[s]];
    Face& b = faces_[side_b[s]];
    a.neighbor[2] = side_b[s];
    b.neighbor[2] = side_a[s];
    // Along each side the chain continues; at the two ends it turns to the other side.
    a.neighbor[0] = first ? side_b[0] : side_a[s - 1];
    a.neighbor[1] = last ? side_b[s] : side_a[s + 1];
    b.neighbor[0] = last ? side_a[s] : side_b[s + 1];
    b.neighbor[1] = first ? side_a[0] : side_b[s - 1];
  }
  if (observer_)
    for (std::size_t s = 0; s < segments; ++s) {
      observer_->face_created(side_a[s]);
      observer_->face_created(side_b[s]);
    }
}

void Tds::clear_faces() {
  for (FaceIndex f = 0; f < faces_.size(); ++f)
    if (faces_[f].alive) destroy_face(f);
  for (FaceIndex& vf : vertex_face_) vf = kNoFace;
}

std::array<FaceIndex, 2> Tds::flip(FaceIndex f, int i) {
  const FaceIndex g = faces_[f].neighbor[static_cast<unsigned>(i)];
  const int j = mirror_index(f, i);
  const Face fo = faces_[f];
  const Face go = faces_[g];
  const VertexIndex a = fo.vertex[static_cast<unsigned>(i)];
  const VertexIndex b = fo.vertex[static_cast<unsigned>(ccw(i))];
  const VertexIndex c = fo.vertex[static_cast<unsigned>(cw(i))];
  const VertexIndex d = go.vertex[static_cast<unsigned>(j)];
  // Outside neighbours of the quadrilateral a-b-d-c, with the edges they share.
  const FaceIndex n_ab = fo.neighbor[static_cast<unsigned>(cw(i))];
  const FaceIndex n_ca = fo.neighbor[static_cast<unsigned>(ccw(i))];
  const FaceIndex n_bd = go.neighbor[static_cast<unsigned>(ccw(j))];
  const FaceIndex n_dc = go.neighbor[static_cast<unsigned>(cw(j))];

  destroy_face(f);
  destroy_face(g);
  // Reuse the two slots in place (destroy pushed them on the free list last).
  free_faces_.resize(free_faces_.size() - 2);
  live_faces_ += 2;
  Face& nf = faces_[f];
  Face& ng = faces_[g];
  nf.vertex = {a, b, d};
  ng.vertex = {a, d, c};
  nf.alive = ng.alive = true;
  link(f, 1, g, 2);  // edge (d, a) opposite b in nf, opposite c in ng
  vertex_face_[a] = f;
  vertex_face_[b] = f;
  vertex_face_[d] = f;
  vertex_face_[c] = g;
  relink_outside(n_bd, b, d, f, 0);
  relink_outside(n_ab, a, b, f, 2);
  relink_outside(n_dc, d, c, g, 0);
  relink_outside(n_ca, c, a, g, 1);
  if (observer_) {
    observer_->face_created(f);
    observer_->face_created(g);
  }
  return {f, g};
}

void Tds::replace_faces(std::span<const FaceIndex> faces, std::span<const BoundaryEdge> boundary,
                        std::span<const std::array<VertexIndex, 3>> triangles, std::vector<FaceIndex>* created) {
  for (FaceIndex f : faces) destroy_face(f);
  // Vertices of destroyed faces get a new face below if they remain in the triangulation;
  // a vertex that only belonged to the hole (the removed one) becomes detached.
  for (FaceIndex f : faces)
    for (VertexIndex v : faces_[f].vertex) vertex_face_[v] = kNoFace;
  for (const BoundaryEdge& e : boundary) {
    vertex_face_[e.from] = e.outside;
    vertex_face_[e.to] = e.outside;
  }

  scratch_faces_.clear();
  scratch_edges_.clear();
  for (const auto& t : triangles) {
    const FaceIndex f = create_face(t[0], t[1], t[2]);
    scratch_faces_.push_back(f);
    for (int i = 0; i < 3; ++i) {
      const VertexIndex from = t[static_cast<unsigned>(ccw(i))];
      const VertexIndex to = t[static_cast<unsigned>(cw(i))];
      const std::uint64_t key = (std::uint64_t{std::min(from, to)} << 32) | std::max(from, to);
      scratch_edges_.push_back({key, f, i, from});
    }
  }
  // Internal edges appear twice (once per direction); pair them after sorting.
  std::sort(scratch_edges_.begin(), scratch_edges_.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return x.key < y.key || (x.key == y.key && x.from < y.from); });
  for (std::size_t k = 0; k < scratch_edges_.size();) {
    if (k + 1 < scratch_edges_.size() && scratch_edges_[k + 1].key == scratch_edges_[k].key &&
        scratch_edges_[k + 1].from != scratch_edges_[k].from) {
      link(scratch_edges_[k].face, scratch_edges_[k].index, scratch_edges_[k + 1].face, scratch_edges_[k + 1].index);
      k += 2;
      continue;
    }
    // A boundary edge: find the outside face that borders it.
    const HalfEdge& h = scratch_edges_[k];
    const Face& nf = faces_[h.face];
    const VertexIndex from = nf.vertex[static_cast<unsigned>(ccw(h.index))];
    const VertexIndex to = nf.vertex[static_cast<unsigned>(cw(h.index))];
    FaceIndex outside = kNoFace;
    for (const BoundaryEdge& e : boundary)
      if (e.from == from && e.to == to) outside = e.outside;
    assert(outside != kNoFace && "new triangle edge is neither internal nor on the boundary");
    relink_outside(outside, from, to, h.face, h.index);
    ++k;
  }
  if (observer_)
    for (FaceIndex f : scratch_faces_) observer_->face_created(f);
  if (created) *created = scratch_faces_;
}

void Tds::incident_faces(VertexIndex v, std::vector<FaceIndex>& out) const {
  out.clear();
  const FaceIndex start = vertex_face_[v];
  if (start == kNoFace) return;
  FaceIndex f = start;
  do {
    out.push_back(f);
    const int i = faces_[f].index_of(v);
    f = faces_[f].neighbor[static_cast<unsigned>(ccw(i))];  // across edge (v, vertex[cw(i)]): the next face ccw
  } while (f != start && out.size() <= faces_.size());
}

void Tds::adjacent_vertices(VertexIndex v, std::vector<VertexIndex>& out) const {
  out.clear();
  const FaceIndex start = vertex_face_[v];
  if (start == kNoFace) return;
  FaceIndex f = start;
  do {
    const int i = faces_[f].index_of(v);
    out.push_back(faces_[f].vertex[static_cast<unsigned>(ccw(i))]);
    f = faces_[f].neighbor[static_cast<unsigned>(ccw(i))];
  } while (f != start && out.size() <= faces_.size());
}

TdsDefect Tds::check() const {
  std::size_t vertices_in = 0;
  for (VertexIndex v = 0; v < vertex_face_.size(); ++v) {
    if (!vertex_alive_[v] || vertex_face_[v] == kNoFace) continue;
    ++vertices_in;
    const FaceIndex f = vertex_face_[v];
    if (f >= faces_.size() || !faces_[f].alive || !faces_[f].has_vertex(v)) return TdsDefect::VertexFaceMismatch;
  }
  if (live_faces_ == 0) return TdsDefect::Valid;
  std::size_t half_edges = 0;
  for (FaceIndex f = 0; f < faces_.size(); ++f) {
    const Face& face = faces_[f];
    if (!face.alive) continue;
    if (face.vertex[0] == face.vertex[1] || face.vertex[1] == face.vertex[2] || face.vertex[0] == face.vertex[2])
      return TdsDefect::DegenerateFace;
    for (int i = 0; i < 3; ++i) {
      ++half_edges;
      const FaceIndex g = face.neighbor[static_cast<unsigned>(i)];
      if (g >= faces_.size() || !faces_[g].alive) return TdsDefect::DeadNeighbor;
      for (VertexIndex v : face.vertex)
        if (!vertex_alive_[v] || vertex_face_[v] == kNoFace) return TdsDefect::OrphanVertex;
      const VertexIndex from = face.vertex[static_cast<unsigned>(ccw(i))];
      const VertexIndex to = face.vertex[static_cast<unsigned>(cw(i))];
      bool found = false;
      for (int j = 0; j < 3 && !found; ++j)
        found = faces_[g].vertex[static_cast<unsigned>(ccw(j))] == to &&
                faces_[g].vertex[static_cast<unsigned>(cw(j))] == from;
      if (!found) return TdsDefect::MismatchedEdge;
      bool back = false;
      for (int j = 0; j < 3 && !back; ++j)
        back = faces_[g].neighbor[static_cast<unsigned>(j)] == f &&
               faces_[g].vertex[static_cast<unsigned>(ccw(j))] == to &&
               faces_[g].vertex[static_cast<unsigned>(cw(j))] == from;
      if (!back) return TdsDefect::AsymmetricAdjacency;
    }
  }
  const auto v = static_cast<long long>(vertices_in);
  const auto e = static_cast<long long>(half_edges / 2);
  const auto fc = static_cast<long long>(live_faces_);
  if (v - e + fc != 2) return TdsDefect::EulerCharacteristic;
  return TdsDefect::Valid;
}

}  // namespace kew::triangulation
