// What a point's own operations do to the triangulation and its schedule: insertion,
// removal, and an update that keeps the model, changes its velocity or reinserts it
// (thesis Eq. 10.1; design §2.3).

#include <cassert>
#include <cmath>

#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/kinetic/sturm.hpp"

namespace kew::kinetic {

using triangulation::ccw;
using triangulation::FaceIndex;
using triangulation::kNoFace;
using triangulation::Trajectory;

PointId KineticDelaunay::insert(double t, Point2 p, Vector2 v) {
  advance_sampled(t);
  const PointId id = dt_.create_vertex(Trajectory{p, v, t});
  if (id >= live_.size()) live_.resize(id + 1, false);
  live_[id] = true;
  if (id >= drift_seq_.size()) {
    drift_seq_.resize(id + 1, 0);
    reported_.resize(id + 1);
  }
  twins_.add(id);
  ++live_points_;
  ++stats_.insertions;
  attach_point(id);
  advance_sampled(now_);  // failures found already due at now are executed before returning
  return id;
}

void KineticDelaunay::remove(PointId id, double t) {
  assert(contains(id));
  advance_sampled(t);
  ++stats_.removals;
  cancel_drift(id);
  detach_point(id);
  schedule_dirty_faces();
  live_[id] = false;
  --live_points_;
  dt_.destroy_vertex(id);
  advance_sampled(now_);
}

UpdateKind KineticDelaunay::update(PointId id, double t, Point2 p, Vector2 v) {
  assert(contains(id));
  advance_sampled(t);
  ++stats_.updates;
  const Point2 predicted = dt_.position(id);
  const double deviation = geometry::norm(p - predicted);
  const double allowed =
      config_.tolerance_mode == ToleranceMode::Absolute ? config_.tolerance : config_.tolerance * geometry::norm(p);
  if (deviation <= allowed && keep_model(id, p, v, deviation, allowed)) {
    ++stats_.kept_updates;
    return UpdateKind::Kept;
  }
  cancel_drift(id);  // the model becomes this report's
  if (deviation <= allowed) {
    // Keep the predicted position exactly, so the triangulation stays valid at now.
    dt_.set_trajectory(id, Trajectory{predicted, v, now_});
    ++stats_.velocity_updates;
    if (twins_.is_twin(id)) {
      schedule_twin_release(id);
    } else {
      revalidate_star(id);
      for (const PointId w : twins_.twins_of(id)) schedule_twin_release(w);
    }
    schedule_dirty_faces();
    advance_sampled(now_);
    return UpdateKind::VelocityOnly;
  }
  ++stats_.reinsertions;
  reinsert(id, Trajectory{p, v, now_});
  advance_sampled(now_);
  return UpdateKind::Reinserted;
}

void KineticDelaunay::reinsert(PointId id, const Trajectory& to) {
  // A report moves an aircraft a few hundred metres at most: the walk that locates it
  // again starts from where it was, not from an arbitrary face (O(1) steps, not O(√n)).
  const PointId anchor = attached_neighbour(id);
  detach_point(id);
  dt_.set_trajectory(id, to);
  const FaceIndex hint =
      anchor != kNoPoint && dt_.tds().is_attached(anchor) ? dt_.tds().vertex_face(anchor) : kNoFace;
  attach_point(id, hint);
}

bool KineticDelaunay::keep_model(PointId id, Point2 p, Vector2 v, double deviation, double allowed) {
  if (config_.keep_model_s <= 0.0 || config_.tolerance_mode != ToleranceMode::Absolute) return false;
  // |model(now + s) − report(now + s)| ≤ deviation + |Δv|·s: within τ until s = slack / |Δv|.
  const double drift_mps = geometry::norm(v - dt_.trajectory(id).velocity);
  const double slack = allowed - deviation;
  if (slack < drift_mps * config_.keep_model_s) return false;
  cancel_drift(id);
  reported_[id] = Trajectory{p, v, now_};
  if (drift_mps > 0.0) {
    const double deadline = now_ + slack / drift_mps;
    if (std::isfinite(deadline)) {
      drift_seq_[id] = queue_.push(deadline, id, 0, EventKind::Drift, 0);
      ++stats_.drifts_queued;
    }
  }
  return true;
}

void KineticDelaunay::cancel_drift(PointId id) {
  if (drift_seq_[id] == 0) return;
  drift_seq_[id] = 0;
  --stats_.drifts_queued;
}

void KineticDelaunay::execute_drift(PointId id) {
  cancel_drift(id);
  ++stats_.drift_reinsertions;
  const Trajectory& report = reported_[id];
  reinsert(id, Trajectory{report.at(now_), report.velocity, now_});
}

void KineticDelaunay::reschedule_star(PointId vertex) {
  // Every certificate whose quadrilateral contains the vertex: all edges of its faces.
  dt_.tds().incident_faces(vertex, scratch_faces_);
  for (const FaceIndex f : scratch_faces_) {
    for (int i = 0; i < 3; ++i) clear_edge(f, i, true);
    dirty_faces_.emplace_back(f, dt_.tds().face(f).generation);
  }
}

bool KineticDelaunay::renewal_still_holds(FaceIndex f, int i, const Polynomial& certificate) const {
  const FaceSchedule& s = schedule_[f];
  if (s.kind[static_cast<unsigned>(i)] != EventKind::Renewal || certificate.is_zero()) return false;
  const double reach = s.time[static_cast<unsigned>(i)] - now_;
  return reach >= 0.0 && certainly_negative(certificate, reach) && !(approach_offset(f, i) < reach);
}

void KineticDelaunay::revalidate_star(PointId vertex) {
  const auto& tds = dt_.tds();
  tds.incident_faces(vertex, scratch_faces_);
  if (dt_.is_flat() || scratch_faces_.empty()) {
    reschedule_star(vertex);
    return;
  }
  // Each face of the star is examined on its link edge (opposite the vertex) and on the
  // spoke opposite ccw(k): around the vertex, that visits every spoke once. First every
  // edge is kept or cleared, then the cleared ones are solved, so that §8.3 windows see
  // only the failures of this velocity, as reschedule_star's would.
  scratch_edges_.clear();
  for (const FaceIndex f : scratch_faces_) {
    const int k = tds.face(f).index_of(vertex);
    for (const int i : {k, ccw(k)}) {
      Polynomial certificate = edge_certificate(f, i);
      if (renewal_still_holds(f, i, certificate)) {
        ++stats_.certificates_kept;
        watch_degenerate(f, i, false);
        tell_edge_listener(f, i);
        continue;
      }
      clear_edge(f, i, true);
      scratch_edges_.push_back({f, i, certificate});
    }
  }
  for (const StarEdge& e : scratch_edges_) {
    solve_edge(e.face, e.edge, 0.0, 0, e.certificate);
    tell_edge_listener(e.face, e.edge);
  }
}

}  // namespace kew::kinetic
