#include "workload.hpp"

#include <algorithm>
#include <numbers>
#include <random>

namespace kew::bench::thesis {
namespace {

// True motion of one aircraft: constant speed, piecewise-constant turn rate. Segments
// last 20–120 s and half of them are straight, so most aircraft fly straight most of
// the time while some turn at up to max_turn — the case where a linear prediction
// drifts and τ decides between a velocity update and a reinsertion.
struct Flight {
  Point2 p;
  double heading = 0.0;  // rad, from the x axis
  double speed = 0.0;
  double turn = 0.0;  // rad/s
  double segment_end = 0.0;

  Vector2 velocity() const { return {speed * std::cos(heading), speed * std::sin(heading)}; }

  void new_segment(double now, double max_turn, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> length(20.0, 120.0), rate(-max_turn, max_turn);
    std::bernoulli_distribution straight(0.5);
    turn = straight(rng) ? 0.0 : rate(rng);
    segment_end = now + length(rng);
  }

  // Moves from `now` to `now + dt` exactly (circular arcs), crossing segment ends.
  void fly(double now, double dt, double max_turn, std::mt19937_64& rng) {
    while (dt > 0) {
      const double h = std::min(dt, segment_end - now);
      if (turn == 0.0) {
        p = p + h * velocity();
      } else {
        const double r = speed / turn, h1 = heading + turn * h;
        p = p + Vector2{r * (std::sin(h1) - std::sin(heading)), r * (std::cos(heading) - std::cos(h1))};
        heading = h1;
      }
      now += h;
      dt -= h;
      if (now >= segment_end) new_segment(now, max_turn, rng);
    }
  }
};

}  // namespace

Workload make_workload(const WorkloadParameters& prm) {
  std::mt19937_64 rng(prm.seed);
  std::uniform_real_distribution<double> pos(0.0, prm.side_m()), speed(prm.speed_min_m_s, prm.speed_max_m_s),
      angle(0.0, 2 * std::numbers::pi);
  std::normal_distribution<double> noise(0.0, prm.noise_sigma_m > 0 ? prm.noise_sigma_m : 1.0);
  const double sigma_scale = prm.noise_sigma_m > 0 ? 1.0 : 0.0;
  const double max_turn = prm.max_turn_deg_s * std::numbers::pi / 180.0;
  const std::size_t n = prm.aircraft;

  // The antenna sweeps the aircraft in a fixed order: aircraft slot[k] is seen at
  // offset (k + ½)·P/N in every period, so times are spread over the period.
  std::vector<std::uint32_t> slot(n);
  for (std::uint32_t i = 0; i < n; ++i) slot[i] = i;
  std::shuffle(slot.begin(), slot.end(), rng);
  std::vector<double> offset(n);
  for (std::size_t k = 0; k < n; ++k)
    offset[slot[k]] = (static_cast<double>(k) + 0.5) * prm.period_s / static_cast<double>(n);

  Workload w;
  w.periods = static_cast<std::size_t>(std::floor(prm.duration_s / prm.period_s));
  w.initial.reserve(n);
  w.updates.reserve(n * w.periods);
  auto measure = [&](double t, std::uint32_t i, const Flight& f) {
    const double dx = sigma_scale * noise(rng), dy = sigma_scale * noise(rng);
    return Measurement{t, i, f.p + Vector2{dx, dy}, f.velocity()};
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    Flight f{{pos(rng), pos(rng)}, angle(rng), speed(rng)};
    f.new_segment(0.0, max_turn, rng);
    w.initial.push_back(measure(0.0, i, f));
    double t = 0.0;
    for (std::size_t k = 0; k < w.periods; ++k) {
      const double next = static_cast<double>(k) * prm.period_s + offset[i];
      f.fly(t, next - t, max_turn, rng);
      t = next;
      w.updates.push_back(measure(t, i, f));
    }
  }
  // The engine's clock only moves forward: replay measurements in time order.
  std::stable_sort(w.updates.begin(), w.updates.end(),
                   [](const Measurement& a, const Measurement& b) { return a.t < b.t; });
  return w;
}

}  // namespace kew::bench::thesis
