// The built-in team's memory: one TeamMember per robot with one field list (visit_fields), and
// snapshots copy through that list, so a member left out of it would not come back with a
// restore. The member count of the structs is counted by the compiler, not written by hand.

#include "team/builtin_team.h"

#include <gtest/gtest.h>

#include "world/field_copy.h"

namespace rescuesim {
namespace {

/// Converts to anything: T{AnyField{}, ...} compiles for as many initialisers as an aggregate T
/// has members (each member is initialised from one).
struct AnyField {
  template <class T>
  operator T&() const&& noexcept;
};
template <class T, class... A>
constexpr std::size_t member_count() {
  if constexpr (requires { T{A{}..., AnyField{}}; }) {
    return member_count<T, A..., AnyField>();
  } else {
    return sizeof...(A);
  }
}

TEST(TeamMemory, EveryMemberOfTheStructsIsInTheFieldList) {
  TeamMember member;
  EXPECT_EQ(listed_fields(member), member_count<TeamMember>()) << "a TeamMember field is missing from visit_fields(TeamMember)";
  TeamMemory memory;
  EXPECT_EQ(listed_fields(memory), member_count<TeamMemory>()) << "a TeamMemory field is missing from visit_fields(TeamMemory)";
}

TEST(TeamMemory, ACopyThroughTheFieldListIsTheOriginal) {
  TeamMemory a;
  a.members.resize(2);
  TeamMember& m = a.members[1];
  m.pending.push_back({VictimIndex(2), Vec3(1, 2, 0.3), std::nullopt});
  m.known = {false, true, false};
  m.found_W = {Vec2(4, 5)};
  m.next_report = SimTime::from_seconds(7);
  m.lost_contact = SimTime::from_seconds(3);
  m.returning = true;
  m.heard.resize(2);
  m.heard[0] = TeamClaim{Vec2(1, 1), Vec2(2, 2), SimTime::from_seconds(6), {Vec2(3, 3)}};
  m.next_share = SimTime::from_seconds(8);
  m.next_seen = SimTime::from_seconds(9);
  m.next_map = SimTime::from_seconds(10);
  m.base_map = MapSquares{0.1, {3, 4}, 1, 1, {MapSquares::occupied}};
  a.relay_check = 17;
  a.base_map_new = true;
  a.next_base_map = SimTime::from_seconds(11);

  TeamMemory b;
  copy_fields(a, b);
  ASSERT_EQ(b.members.size(), 2u);
  const TeamMember& c = b.members[1];
  ASSERT_EQ(c.pending.size(), 1u);
  EXPECT_EQ(c.pending[0].victim, VictimIndex(2));
  EXPECT_EQ(c.pending[0].p_W, Vec3(1, 2, 0.3));
  EXPECT_EQ(c.known, m.known);
  EXPECT_EQ(c.found_W, m.found_W);
  EXPECT_EQ(c.next_report, m.next_report);
  EXPECT_EQ(c.lost_contact, m.lost_contact);
  EXPECT_TRUE(c.returning);
  ASSERT_EQ(c.heard.size(), 2u);
  ASSERT_TRUE(c.heard[0].has_value());
  EXPECT_EQ(c.heard[0]->going, std::optional<Vec2>(Vec2(2, 2)));
  EXPECT_EQ(c.heard[0]->stamp, SimTime::from_seconds(6));
  EXPECT_FALSE(c.heard[1].has_value());
  EXPECT_EQ(c.next_share, m.next_share);
  EXPECT_EQ(c.next_seen, m.next_seen);
  EXPECT_EQ(c.next_map, m.next_map);
  ASSERT_TRUE(c.base_map.has_value());
  EXPECT_EQ(c.base_map->origin, std::make_pair(3, 4));
  EXPECT_EQ(c.base_map->states, m.base_map->states);
  EXPECT_EQ(b.relay_check, 17u);
  EXPECT_TRUE(b.base_map_new);
  EXPECT_EQ(b.next_base_map, SimTime::from_seconds(11));
  // the first member stayed at its defaults
  EXPECT_EQ(b.members[0].lost_contact, SimTime{-1});
}

}  // namespace
}  // namespace rescuesim
