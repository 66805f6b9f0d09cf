#pragma once
// The volumes within reach of a path (design §4.11): a Boost.Geometry R-tree of boxes in
// longitude and latitude, so that thousands of volumes cost a track little more than
// none. A box is conservative: it holds every point within a distance of a centre (the
// geodesic disk of a volume's extent, or of a path's length), split in two across the
// antimeridian and widened to every longitude near a pole. The candidates of a path are
// every volume whose box meets the path's: a superset of those entry() can find, never a
// volume it misses.

#include <cstdint>
#include <memory>
#include <vector>

#include "kew/volume/entry.hpp"
#include "kew/volume/volume.hpp"

namespace kew::volume {

/// A box in degrees: west ≤ east (never across ±180: such a disk is two boxes).
struct DegreeBox {
  double south_deg, west_deg, north_deg, east_deg;
};

/// Boxes that together hold every point within `radius_m` (m, ≥ 0) of `centre` on WGS84:
/// one box, or two across the antimeridian; [−180, 180] in longitude when the disk comes
/// within a degree of a pole.
std::vector<DegreeBox> disk_boxes(LatLon centre, double radius_m);

class VolumeIndex {
 public:
  /// Indexes `areas` (their positions in the vector are the indices returned).
  explicit VolumeIndex(const std::vector<Volume>& areas);
  ~VolumeIndex();
  VolumeIndex(VolumeIndex&&) noexcept;
  VolumeIndex& operator=(VolumeIndex&&) noexcept;

  /// The indices, ascending and each once, of the volumes whose boxes meet the box of
  /// the path of `motion` over `horizon_s` (s): every volume the path can enter.
  std::vector<std::uint32_t> candidates(const Motion& motion, double horizon_s) const;
  /// The same for every point within `radius_m` of `centre`.
  std::vector<std::uint32_t> near(LatLon centre, double radius_m) const;
  std::size_t size() const { return size_; }

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
  std::size_t size_ = 0;
};

}  // namespace kew::volume
