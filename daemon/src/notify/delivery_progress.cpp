#include "delivery_progress.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <simdjson.h>

namespace kew::daemon {

bool DeliveryProgress::covers(std::uint64_t seq) const {
  return seq <= through || std::binary_search(also.begin(), also.end(), seq);
}

std::string DeliveryProgress::to_json() const {
  return fmt::format("{{\"through\":{},\"also\":[{}]}}", through, fmt::join(also, ","));
}

std::optional<DeliveryProgress> DeliveryProgress::from_json(std::string_view text) {
  simdjson::dom::parser parser;
  simdjson::dom::element document;
  simdjson::dom::array also;
  DeliveryProgress progress;
  if (parser.parse(text.data(), text.size()).get(document) != simdjson::SUCCESS ||
      document["through"].get(progress.through) != simdjson::SUCCESS ||
      document["also"].get(also) != simdjson::SUCCESS)
    return std::nullopt;
  for (const simdjson::dom::element value : also) {
    std::uint64_t seq = 0;
    if (value.get(seq) != simdjson::SUCCESS) return std::nullopt;
    progress.also.push_back(seq);
  }
  std::sort(progress.also.begin(), progress.also.end());
  std::erase_if(progress.also, [&](std::uint64_t seq) { return seq <= progress.through; });
  return progress;
}

void DeliveryProgress::merge(const DeliveryProgress& other) {
  std::vector<std::uint64_t> all;
  std::set_union(also.begin(), also.end(), other.also.begin(), other.also.end(), std::back_inserter(all));
  through = std::max(through, other.through);
  all.erase(std::unique(all.begin(), all.end()), all.end());
  std::erase_if(all, [&](std::uint64_t seq) { return seq <= through; });
  // A run of delivered events just above `through` moves it on.
  std::size_t i = 0;
  while (i < all.size() && all[i] == through + 1) ++through, ++i;
  all.erase(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(i));
  also = std::move(all);
}

}  // namespace kew::daemon
