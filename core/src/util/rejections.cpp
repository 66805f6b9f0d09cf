#include "kew/util/rejections.hpp"

namespace kew {

namespace {
bool is_power_of_two(std::uint64_t v) { return v != 0 && (v & (v - 1)) == 0; }
}  // namespace

void Rejections::reject(std::string_view reason, std::string_view message) {
  ++total_;
  auto it = counts_.find(reason);
  if (it == counts_.end()) it = counts_.emplace(std::string(reason), 0).first;
  const std::uint64_t n = ++it->second;
  last_.assign(reason);
  if (!reporter_) return;
  const bool in_burst = n <= burst_;
  const bool sampled = burst_ > 0 && n % burst_ == 0 && is_power_of_two(n / burst_);
  if (in_burst || sampled) reporter_(reason, message);
}

std::uint64_t Rejections::count(std::string_view reason) const {
  const auto it = counts_.find(reason);
  return it == counts_.end() ? 0 : it->second;
}

void Rejections::merge(const Rejections& other) {
  for (const auto& [reason, n] : other.counts_) counts_[reason] += n;
  total_ += other.total_;
}

void Rejections::save(util::CheckpointWriter& out) const {
  out.tag("rejections");
  out.u64(total_);
  out.text(last_);
  out.u64(counts_.size());
  for (const auto& [reason, n] : counts_) {
    out.text(reason);
    out.u64(n);
  }
}

void Rejections::restore(util::CheckpointReader& in) {
  // Read whole before anything changes: a checkpoint that cannot be read leaves the counts.
  in.tag("rejections");
  const std::uint64_t total = in.u64();
  std::string last = in.text();
  std::map<std::string, std::uint64_t, std::less<>> counts;
  const std::uint64_t reasons = in.u64();
  for (std::uint64_t i = 0; i < reasons; ++i) {
    std::string reason = in.text();
    counts[std::move(reason)] = in.u64();
  }
  total_ = total;
  last_ = std::move(last);
  counts_ = std::move(counts);
}

}  // namespace kew
