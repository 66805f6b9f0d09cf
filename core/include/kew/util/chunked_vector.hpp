#pragma once
// A growable array stored in fixed chunks of kChunk elements. Growth allocates one more
// chunk and never moves an element, so memory in use stays within one chunk of size()
// (a std::vector holds up to twice its size after doubling, 1.4 times on average), and
// references stay valid while the array grows. Indexing costs one more load than a
// vector; use it for large per-track records, not for arrays in the innermost loops.

#include <cstddef>
#include <memory>
#include <vector>

namespace kew::util {

template <class T, std::size_t kChunk = 128>
class ChunkedVector {
  static_assert(kChunk > 0 && (kChunk & (kChunk - 1)) == 0, "chunk length must be a power of two");

 public:
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  /// Elements that fit in the chunks allocated now (size() ≤ capacity() < size() + kChunk).
  std::size_t capacity() const { return chunks_.size() * kChunk; }

  T& operator[](std::size_t i) { return chunks_[i / kChunk][i % kChunk]; }
  const T& operator[](std::size_t i) const { return chunks_[i / kChunk][i % kChunk]; }

  /// Appends a value-initialised element and returns it.
  T& emplace_back() {
    if (size_ == capacity()) chunks_.push_back(std::make_unique<T[]>(kChunk));
    return (*this)[size_++];
  }

 private:
  std::vector<std::unique_ptr<T[]>> chunks_;
  std::size_t size_ = 0;
};

}  // namespace kew::util
