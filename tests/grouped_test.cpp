// group_by_key (lccp/core/grouped.hpp): the one counting sort the stages after
// growth group their items with.
#include "lccp/core/grouped.hpp"

#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace lccp {
namespace {

std::vector<std::string> group(const Grouped<std::string>& g, std::size_t k) { return {g[k].begin(), g[k].end()}; }

TEST(GroupByKey, EachGroupHoldsItsItemsInTheOrderTheyCame) {
  const std::vector<std::pair<std::uint32_t, std::string>> items{
      {2, "a"}, {0, "b"}, {2, "c"}, {3, "d"}, {0, "e"}, {2, "f"}};
  const Grouped<std::string> g = group_by_key<std::string>(5, [&](auto emit) {
    for (const auto& [key, item] : items) emit(key, item);
  });
  ASSERT_EQ(g.size(), 5u);
  EXPECT_EQ(g.offsets, (std::vector<std::uint32_t>{0, 2, 2, 5, 6, 6}));
  EXPECT_EQ(group(g, 0), (std::vector<std::string>{"b", "e"}));
  EXPECT_TRUE(g[1].empty());
  EXPECT_EQ(group(g, 2), (std::vector<std::string>{"a", "c", "f"}));
  EXPECT_EQ(group(g, 3), (std::vector<std::string>{"d"}));
  EXPECT_TRUE(g[4].empty());  // a key past the last item's
}

TEST(GroupByKey, NoItemsGiveEmptyGroupsAndNoKeysNoGroups) {
  const auto none = [](auto) {};
  const Grouped<int> three = group_by_key<int>(3, none);
  ASSERT_EQ(three.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_TRUE(three[k].empty());
  EXPECT_TRUE(three.items.empty());
  EXPECT_EQ(group_by_key<int>(0, none).size(), 0u);
}

}  // namespace
}  // namespace lccp
