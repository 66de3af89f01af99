// The J range of an assembly pass (continuum/jacobian_range.hpp): the smallest and the largest
// J = det F with their element and point, and the same answer however the elements were spread
// over threads (equal values keep the first element and point).
#include <gtest/gtest.h>

#include <vector>

#include "continuum/jacobian_range.hpp"

namespace isomuscle::continuum {
namespace {

TEST(JacobianRange, EmptyUntilAPointIsTaken) {
  JacobianRange r;
  EXPECT_FALSE(r.found());
  r.take(JacobianRange{});
  EXPECT_FALSE(r.found());
  r.take_element(3, std::vector<double>{});
  EXPECT_FALSE(r.found());
}

TEST(JacobianRange, SmallestAndLargestWithTheirPoints) {
  JacobianRange r;
  r.take_element(0, std::vector<double>{1.0, 0.93, 1.02});
  r.take_element(1, std::vector<double>{1.21, 0.99});
  r.take_element(2, std::vector<double>{0.86, 1.0, 1.0, 1.05});
  ASSERT_TRUE(r.found());
  EXPECT_EQ(r.smallest.value, 0.86);
  EXPECT_EQ(r.smallest.element, 2);
  EXPECT_EQ(r.smallest.point, 0);
  EXPECT_EQ(r.largest.value, 1.21);
  EXPECT_EQ(r.largest.element, 1);
  EXPECT_EQ(r.largest.point, 0);
}

TEST(JacobianRange, ThreadsGiveTheSameRangeInAnyOrder) {
  // Element e has J = {1 - 0.1 e, 1 + 0.1 e} except that elements 2 and 5 tie at both ends; the
  // tie goes to the smaller element whichever thread saw it.
  const auto element_J = [](int e) {
    const int k = e == 5 ? 2 : e;
    return std::vector<double>{1.0 - 0.1 * k, 1.0 + 0.1 * k};
  };
  const std::vector<std::vector<int>> spreads = {{0, 1, 2, 3, 4, 5}, {5, 4, 3, 2, 1, 0}};
  for (const std::vector<int>& order : spreads) {
    std::vector<JacobianRange> threads(3);
    for (std::size_t i = 0; i < order.size(); ++i)
      threads[i % threads.size()].take_element(order[i], element_J(order[i]));
    const JacobianRange r = JacobianRange::of(threads);
    EXPECT_DOUBLE_EQ(r.smallest.value, 0.6);
    EXPECT_EQ(r.smallest.element, 4);
    EXPECT_DOUBLE_EQ(r.largest.value, 1.4);
    EXPECT_EQ(r.largest.element, 4);
    EXPECT_EQ(r.largest.point, 1);
  }
  // Only the tied elements: element 2 wins at both ends.
  for (const std::vector<int>& order : {std::vector<int>{2, 5}, std::vector<int>{5, 2}}) {
    std::vector<JacobianRange> threads(2);
    threads[0].take_element(order[0], element_J(order[0]));
    threads[1].take_element(order[1], element_J(order[1]));
    const JacobianRange r = JacobianRange::of(threads);
    EXPECT_EQ(r.smallest.element, 2);
    EXPECT_EQ(r.largest.element, 2);
  }
}

}  // namespace
}  // namespace isomuscle::continuum
