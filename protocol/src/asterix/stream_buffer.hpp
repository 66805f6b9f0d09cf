#pragma once
// Holds the bytes of an incomplete message between feed() calls, so that a framing's
// parser always sees contiguous bytes and the reports do not depend on how the stream was
// split.
//
// Parser contract: `std::size_t parse(std::span<const std::uint8_t> bytes, bool at_end)`
// returns how many leading bytes it has finished with. Without at_end it stops before a
// message it cannot yet decide on (so what is left is less than one message plus the
// parser's look-ahead); with at_end it must finish with everything.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace kew::protocol::asterix {

class StreamBuffer {
 public:
  template <class Parse>
  void feed(std::span<const std::uint8_t> input, Parse&& parse) {
    while (!input.empty()) {
      if (pending_.empty()) {
        // Common case: parse straight from the caller's bytes, keep only the tail.
        const std::size_t used = parse(input, false);
        input = input.subspan(used);
        pending_.assign(input.begin(), input.end());
        return;
      }
      // Top up in bounded steps so one huge feed() is not copied whole.
      const std::size_t take = std::min(input.size(), kTopUpBytes);
      pending_.insert(pending_.end(), input.begin(), input.begin() + static_cast<std::ptrdiff_t>(take));
      input = input.subspan(take);
      const std::size_t used = parse(std::span<const std::uint8_t>(pending_), false);
      pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(used));
    }
  }

  template <class Parse>
  void finish(Parse&& parse) {
    parse(std::span<const std::uint8_t>(pending_), true);
    pending_.clear();
  }

  std::size_t pending_bytes() const { return pending_.size(); }

 private:
  static constexpr std::size_t kTopUpBytes = 64 * 1024;
  std::vector<std::uint8_t> pending_;
};

}  // namespace kew::protocol::asterix
