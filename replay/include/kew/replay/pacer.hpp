#pragma once
// Pacing of a replay like the recording (gpsfake-style, design §5.6): a record of data
// time t is released at wall time w0 + (t − t0)/speed, where t0 and w0 are the first
// record's data time and wall time.

#include <chrono>

namespace kew::replay {

class Pacer {
 public:
  /// `speed` > 0: multiple of real time; 0: as fast as possible (no waiting).
  explicit Pacer(double speed) : speed_(speed) {}

  /// Wall-clock instant at which a record of data time `t` (UTC s) is due; the
  /// distant past when not pacing.
  std::chrono::steady_clock::time_point due(double t) {
    if (speed_ <= 0.0) return std::chrono::steady_clock::time_point::min();
    const auto now = std::chrono::steady_clock::now();
    if (!started_) {
      started_ = true;
      t0_ = t;
      w0_ = now;
    }
    if (t <= t0_) return w0_;
    return w0_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>((t - t0_) / speed_));
  }

 private:
  double speed_;
  bool started_ = false;
  double t0_ = 0.0;
  std::chrono::steady_clock::time_point w0_;
};

}  // namespace kew::replay
