#include "kew/kinetic/twin_registry.hpp"

#include <algorithm>
#include <cassert>

#include "kew/util/gentle_growth.hpp"

namespace kew::kinetic {

void TwinRegistry::add(PointId id) {
  util::grow_to(twin_host_, id + 1, kNoPoint);
  util::grow_to(twins_, id + 1);
  util::grow_to(release_seq_, id + 1, std::uint64_t{0});
  twin_host_[id] = kNoPoint;
  twins_[id].clear();
  release_seq_[id] = 0;
}

void TwinRegistry::make_twin(PointId id, PointId host) {
  host = host_of(host);
  assert(host != id && !is_twin(id) && twins_[id].empty());
  twin_host_[id] = host;
  twins_[host].push_back(id);
}

void TwinRegistry::unlink(PointId id) {
  std::erase(twins_[twin_host_[id]], id);
  twin_host_[id] = kNoPoint;
  release_seq_[id] = 0;
}

std::vector<PointId> TwinRegistry::release_all(PointId vertex) {
  std::vector<PointId> released = std::move(twins_[vertex]);
  twins_[vertex].clear();
  for (const PointId w : released) {
    twin_host_[w] = kNoPoint;
    release_seq_[w] = 0;
  }
  return released;
}

std::span<const PointId> TwinRegistry::merge_into(PointId vertex, PointId host) {
  host = host_of(host);
  assert(host != vertex && !is_twin(vertex));
  std::vector<PointId>& joined = twins_[host];
  const std::size_t first = joined.size();
  twin_host_[vertex] = host;
  joined.push_back(vertex);
  for (const PointId w : twins_[vertex]) {
    twin_host_[w] = host;
    joined.push_back(w);
  }
  twins_[vertex].clear();
  return std::span<const PointId>(joined).subspan(first);
}

bool TwinRegistry::is_valid() const {
  const std::size_t n = twin_host_.size();
  for (PointId id = 0; id < n; ++id) {
    const PointId host = twin_host_[id];
    if (host == kNoPoint) {
      if (release_seq_[id] != 0) return false;
    } else if (host >= n || host == id || is_twin(host) || std::count(twins_[host].begin(), twins_[host].end(), id) != 1) {
      return false;
    }
    // With the check above, this also keeps a twin from listing twins of its own.
    for (const PointId w : twins_[id])
      if (w >= n || twin_host_[w] != id) return false;
  }
  return true;
}

}  // namespace kew::kinetic
