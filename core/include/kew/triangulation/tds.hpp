#pragma once
// Triangulation data structure: the combinatorics of a triangulated sphere, with no
// geometry. Vertex 0 is the infinite vertex, so the unbounded hull is a ring of
// ordinary faces around it (no giant bounding triangle). Faces are counter-clockwise
// vertex triples; neighbour i lies across the edge opposite vertex i.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace kew::triangulation {

using VertexIndex = std::uint32_t;
using FaceIndex = std::uint32_t;
inline constexpr VertexIndex kInfiniteVertex = 0;
inline constexpr FaceIndex kNoFace = 0xFFFFFFFFu;
inline constexpr VertexIndex kNoVertex = 0xFFFFFFFFu;

constexpr int ccw(int i) { return i == 2 ? 0 : i + 1; }
constexpr int cw(int i) { return i == 0 ? 2 : i - 1; }

struct Face {
  std::array<VertexIndex, 3> vertex{};
  std::array<FaceIndex, 3> neighbor{kNoFace, kNoFace, kNoFace};
  /// Bumped whenever the slot's face is destroyed, so holders of (face, generation)
  /// pairs, such as scheduled events, can tell a stale reference from a live one.
  std::uint32_t generation = 0;
  bool alive = false;

  bool has_vertex(VertexIndex v) const { return vertex[0] == v || vertex[1] == v || vertex[2] == v; }
  bool is_infinite() const { return has_vertex(kInfiniteVertex); }
  int index_of(VertexIndex v) const { return vertex[0] == v ? 0 : vertex[1] == v ? 1 : vertex[2] == v ? 2 : -1; }
};

/// Told about every face that appears or disappears, in the order it happens.
class FaceObserver {
 public:
  virtual ~FaceObserver() = default;
  virtual void face_created(FaceIndex f) = 0;
  virtual void face_destroyed(FaceIndex f) = 0;
};

/// A directed edge of a hole's boundary: the hole lies on the left of from→to, and
/// `outside` is the face on the right (it stays).
struct BoundaryEdge {
  VertexIndex from;
  VertexIndex to;
  FaceIndex outside;
};

/// Why a structure is not valid; Valid when it is.
enum class TdsDefect {
  Valid,
  DeadNeighbor,          // a live face points at a dead or missing face
  AsymmetricAdjacency,   // g is f's neighbour but f is not g's across the same edge
  MismatchedEdge,        // neighbours disagree on the vertices of their common edge
  DegenerateFace,        // a face repeats a vertex
  VertexFaceMismatch,    // a vertex's face does not contain it
  EulerCharacteristic,   // V - E + F != 2 for the sphere
  OrphanVertex,          // a vertex marked in the triangulation has no face
};

class Tds {
 public:
  Tds();

  void set_observer(FaceObserver* observer) { observer_ = observer; }

  /// A new vertex record, detached (in no face) until faces are made around it.
  VertexIndex create_vertex();
  /// Releases a detached vertex record for reuse.
  void destroy_vertex(VertexIndex v);
  bool vertex_alive(VertexIndex v) const { return v < vertex_alive_.size() && vertex_alive_[v]; }
  /// A face containing v, or kNoFace when v is detached.
  FaceIndex vertex_face(VertexIndex v) const { return vertex_face_[v]; }
  bool is_attached(VertexIndex v) const { return vertex_alive(v) && vertex_face_[v] != kNoFace; }
  std::size_t vertex_capacity() const { return vertex_alive_.size(); }

  const Face& face(FaceIndex f) const { return faces_[f]; }
  std::size_t face_capacity() const { return faces_.size(); }
  std::size_t face_count() const { return live_faces_; }
  /// Any live face, kNoFace when there are none.
  FaceIndex any_face() const;

  /// Index j such that face(neighbor(f,i)).neighbor[j] == f across the same edge.
  int mirror_index(FaceIndex f, int i) const;

  /// The flat structure of collinear vertices given in order along their line: two
  /// infinite faces per segment, one on each side (at least two vertices, no faces yet).
  void make_chain(std::span<const VertexIndex> ordered);
  /// Removes every face and detaches every vertex.
  void clear_faces();

  /// Replaces the edge opposite vertex i of f by the other diagonal of the quadrilateral
  /// formed with its neighbour. The two slots are reused (generations bumped);
  /// returns them: the first holds the old f.vertex[i].
  std::array<FaceIndex, 2> flip(FaceIndex f, int i);

  /// Destroys `faces` (a hole whose boundary is `boundary`) and fills the hole with
  /// `triangles`, linking them to each other and to the outside faces.
  void replace_faces(std::span<const FaceIndex> faces, std::span<const BoundaryEdge> boundary,
                     std::span<const std::array<VertexIndex, 3>> triangles,
                     std::vector<FaceIndex>* created = nullptr);

  /// Faces around v in counter-clockwise order, starting from vertex_face(v).
  void incident_faces(VertexIndex v, std::vector<FaceIndex>& out) const;
  /// Vertices adjacent to v in counter-clockwise order (may include the infinite vertex).
  void adjacent_vertices(VertexIndex v, std::vector<VertexIndex>& out) const;
  /// Calls f(w) for every vertex w adjacent to v, in the order adjacent_vertices() gives
  /// (the infinite vertex included, a flat chain's end neighbour twice), without
  /// allocating: the probe's breadth-first search visits ~100 vertices per update.
  template <class F>
  void for_each_adjacent_vertex(VertexIndex v, F&& f) const {
    const FaceIndex start = vertex_face_[v];
    if (start == kNoFace) return;
    FaceIndex f_index = start;
    std::size_t visited = 0;
    do {
      const Face& face = faces_[f_index];
      const auto next = static_cast<unsigned>(ccw(face.index_of(v)));
      f(face.vertex[next]);
      f_index = face.neighbor[next];
    } while (f_index != start && ++visited <= faces_.size());  // bound: a corrupt ring cannot loop forever
  }

  /// Combinatorial validity of the whole structure; O(V + F).
  TdsDefect check() const;
  bool is_valid() const { return check() == TdsDefect::Valid; }

 private:
  FaceIndex create_face(VertexIndex a, VertexIndex b, VertexIndex c);
  void destroy_face(FaceIndex f);
  void link(FaceIndex f, int i, FaceIndex g, int j);
  /// Points the outside face's entry for edge (a, b) at `inside`.
  void relink_outside(FaceIndex outside, VertexIndex a, VertexIndex b, FaceIndex inside, int inside_index);

  std::vector<Face> faces_;
  std::vector<FaceIndex> free_faces_;
  std::size_t live_faces_ = 0;
  std::vector<FaceIndex> vertex_face_;
  std::vector<bool> vertex_alive_;
  std::vector<VertexIndex> free_vertices_;
  FaceObserver* observer_ = nullptr;

  struct HalfEdge {
    std::uint64_t key;  // min(a,b) << 32 | max(a,b)
    FaceIndex face;
    int index;
    VertexIndex from;
  };
  std::vector<HalfEdge> scratch_edges_;
  std::vector<FaceIndex> scratch_faces_;
};

}  // namespace kew::triangulation
