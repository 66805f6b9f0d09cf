// TrackIndex against a reference map under random inserts and erases. Hashes are drawn
// from a few values so that runs collide, wrap around the end of the table and are cut
// by erases: exactly the cases backward-shift deletion must get right.

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>

#include "kew/track/track_index.hpp"

namespace {

using kew::track::TrackIndex;

struct Reference {
  std::map<TrackIndex::Slot, std::uint32_t> hash_of;  // live slot → its hash
};

void expect_same(const TrackIndex& index, const Reference& ref, TrackIndex::Slot slots) {
  ASSERT_TRUE(index.is_valid());
  ASSERT_EQ(index.size(), ref.hash_of.size());
  for (TrackIndex::Slot s = 0; s < slots; ++s) {
    const auto it = ref.hash_of.find(s);
    // The key of slot s is s itself; look it up under the hash it was stored with.
    const std::uint32_t h = it != ref.hash_of.end() ? it->second : s % 7u;
    const TrackIndex::Slot found = index.find(h, [&](TrackIndex::Slot candidate) { return candidate == s; });
    ASSERT_EQ(found, it != ref.hash_of.end() ? s : TrackIndex::kAbsent) << "slot " << s;
  }
}

class TrackIndexProperty : public ::testing::TestWithParam<unsigned> {};

TEST_P(TrackIndexProperty, AgreesWithAMapUnderRandomInsertsAndErases) {
  std::mt19937 rng(GetParam());
  const TrackIndex::Slot slots = 300;
  // A handful of hashes, some just below a power of two so runs wrap the table's end.
  const std::uint32_t hashes[] = {0u, 1u, 5u, 15u, 31u, 63u, 0xffffffffu, 0x7fffffffu, 12345u};
  std::uniform_int_distribution<TrackIndex::Slot> pick_slot(0, slots - 1);
  std::uniform_int_distribution<std::size_t> pick_hash(0, std::size(hashes) - 1);
  TrackIndex index;
  Reference ref;
  for (int step = 0; step < 4000; ++step) {
    const TrackIndex::Slot s = pick_slot(rng);
    const auto it = ref.hash_of.find(s);
    if (it == ref.hash_of.end()) {
      const std::uint32_t h = hashes[pick_hash(rng)];
      index.insert(h, s);
      ref.hash_of.emplace(s, h);
    } else {
      ASSERT_TRUE(index.erase(it->second, s));
      ASSERT_FALSE(index.erase(it->second, s)) << "erased twice";
      ref.hash_of.erase(it);
    }
    if (step % 50 == 0 || step > 3900) expect_same(index, ref, slots);
  }
  expect_same(index, ref, slots);
}

INSTANTIATE_TEST_SUITE_P(Seeds, TrackIndexProperty, ::testing::Values(1u, 2u, 3u, 4u, 5u));

TEST(TrackIndex, FindsEveryKeyByItsStringsAfterChurn) {
  std::vector<std::pair<std::string, std::string>> keys;
  for (int i = 0; i < 5000; ++i) keys.emplace_back(i % 3 == 0 ? "radar-a" : "adsb", "id" + std::to_string(i));
  TrackIndex index;
  const auto find = [&](std::size_t k) {
    return index.find(TrackIndex::hash(keys[k].first, keys[k].second),
                      [&](TrackIndex::Slot s) { return keys[s] == keys[k]; });
  };
  for (std::size_t k = 0; k < keys.size(); ++k) index.insert(TrackIndex::hash(keys[k].first, keys[k].second), static_cast<TrackIndex::Slot>(k));
  for (std::size_t k = 0; k < keys.size(); k += 2)
    ASSERT_TRUE(index.erase(TrackIndex::hash(keys[k].first, keys[k].second), static_cast<TrackIndex::Slot>(k)));
  ASSERT_TRUE(index.is_valid());
  EXPECT_EQ(index.size(), keys.size() / 2);
  for (std::size_t k = 0; k < keys.size(); ++k)
    EXPECT_EQ(find(k), k % 2 == 0 ? TrackIndex::kAbsent : k) << keys[k].second;
  // Source and id are not interchangeable.
  EXPECT_NE(TrackIndex::hash("a", "b"), TrackIndex::hash("b", "a"));
  EXPECT_LE(2 * index.size(), index.capacity());
}

}  // namespace
