// Typed indices (core/index.h): a robot's index is not a victim's, an int or a size_t, and a
// per-robot vector takes only robot indices. The compile-time half is static_asserts: if any of
// them stops holding, this file stops compiling.
#include "core/index.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <type_traits>
#include <unordered_set>
#include <vector>

namespace rescuesim {
namespace {

// a mixed-up index does not compile
static_assert(!std::is_convertible_v<RobotIndex, VictimIndex>);
static_assert(!std::is_constructible_v<VictimIndex, RobotIndex>);
static_assert(!std::is_convertible_v<int, RobotIndex>);
static_assert(!std::is_convertible_v<std::size_t, RobotIndex>);
static_assert(!std::is_convertible_v<RobotIndex, int>);
static_assert(!std::is_convertible_v<RobotIndex, std::size_t>);
static_assert(!std::is_convertible_v<RadioNodeIndex, RobotIndex>);
template <class V, class I>
concept Subscriptable = requires(V v, I i) {
  v[i];
};
static_assert(Subscriptable<IndexedVector<RobotTag, double>, RobotIndex>);
static_assert(!Subscriptable<IndexedVector<RobotTag, double>, VictimIndex>);
static_assert(!Subscriptable<IndexedVector<RobotTag, double>, int>);
static_assert(!Subscriptable<IndexedVector<RobotTag, double>, std::size_t>);
// as cheap as the int it holds
static_assert(sizeof(RobotIndex) == sizeof(int));
static_assert(std::is_trivially_copyable_v<RobotIndex>);

TEST(Index, DefaultIsInvalidAndNegativeValuesAreInvalid) {
  EXPECT_FALSE(RobotIndex().valid());
  EXPECT_EQ(RobotIndex().value(), -1);
  EXPECT_EQ(RobotIndex(-7).value(), -1);
  EXPECT_EQ(RobotIndex(-7), RobotIndex());
  EXPECT_TRUE(RobotIndex(0).valid());
  EXPECT_EQ(RobotIndex(3).slot(), 3u);
  EXPECT_DEATH((void)RobotIndex().slot(), "invalid index");
}

TEST(Index, OrdersAndCountsLikeItsNumber) {
  RobotIndex r(2);
  EXPECT_LT(RobotIndex(1), r);
  EXPECT_EQ(r++, RobotIndex(2));
  EXPECT_EQ(r, RobotIndex(3));
  EXPECT_EQ(++r, RobotIndex(4));
  EXPECT_EQ(RobotIndex::at(5), RobotIndex(5));
  EXPECT_DEATH((void)RobotIndex::at(std::size_t{1} << 40), "beyond int");
  std::unordered_set<RobotIndex> set{RobotIndex(1), RobotIndex(1), RobotIndex(2)};
  EXPECT_EQ(set.size(), 2u);
}

TEST(Index, RangeVisitsZeroToCountMinusOne) {
  std::vector<int> seen;
  for (RobotIndex r : indices<RobotTag>(4)) seen.push_back(r.value());
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3}));
  int none = 0;
  for (RobotIndex r : indices<RobotTag>(0)) none += r.value() + 1;
  EXPECT_EQ(none, 0);
}

TEST(IndexedVector, IsAddressedByItsIndexAndBehavesAsAVector) {
  IndexedVector<RobotTag, double> travelled(3, 0.5);
  travelled[RobotIndex(1)] += 2.0;
  EXPECT_EQ(travelled[RobotIndex(1)], 2.5);
  EXPECT_EQ(travelled.size(), 3u);
  double sum = 0;
  for (double d : travelled) sum += d;
  EXPECT_DOUBLE_EQ(sum, 3.5);
  EXPECT_EQ(travelled.next_index(), RobotIndex(3));
  travelled.push_back(9);
  EXPECT_TRUE(travelled.contains(RobotIndex(3)));
  EXPECT_FALSE(travelled.contains(RobotIndex(4)));
  EXPECT_FALSE(travelled.contains(RobotIndex()));
  EXPECT_THROW((void)travelled.at(RobotIndex(4)), std::out_of_range);
  // erase moves the ones after down one index, as remove_robot does
  travelled.erase(RobotIndex(1));
  EXPECT_EQ(travelled.vector(), (std::vector<double>{0.5, 0.5, 9}));
  int visited = 0;
  for (RobotIndex r : travelled.indices()) visited += r.value();
  EXPECT_EQ(visited, 0 + 1 + 2);
}

}  // namespace
}  // namespace rescuesim
