// parallel_for: every index exactly once, results in their own slots, the lowest failing index's
// exception rethrown.
#include <boost/test/unit_test.hpp>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "dcshell/parallel_for.h"

using namespace dcshell;

BOOST_AUTO_TEST_SUITE(parallel)

BOOST_AUTO_TEST_CASE(every_index_once_in_its_slot) {
  for (unsigned threads : {1u, 2u, 7u, 0u}) {
    std::vector<int> hits(1000, 0);
    std::vector<long> out(1000, -1);
    parallel_for(hits.size(), [&](std::size_t i) {
      ++hits[i];
      out[i] = long(i) * long(i);
    }, threads);
    for (std::size_t i = 0; i < hits.size(); ++i) {
      BOOST_TEST(hits[i] == 1);
      BOOST_TEST(out[i] == long(i) * long(i));
    }
  }
  std::atomic<int> calls{0};
  parallel_for(0, [&](std::size_t) { ++calls; }, 4);
  BOOST_TEST(calls.load() == 0);
}

BOOST_AUTO_TEST_CASE(lowest_failing_index_is_rethrown) {
  // Items 3 and 5 throw; with one thread the scan stops at 3; with more, 5 may run first, but
  // 3 is always handed out before 5 and its error wins.
  for (unsigned threads : {1u, 2u, 4u}) {
    try {
      parallel_for(8, [](std::size_t i) {
        if (i == 3 || i == 5) throw std::runtime_error("item " + std::to_string(i));
      }, threads);
      BOOST_FAIL("no exception");
    } catch (const std::runtime_error& e) {
      BOOST_TEST(std::string(e.what()) == "item 3");
    }
  }
}

BOOST_AUTO_TEST_CASE(largest_first_orders_by_decreasing_cost_ties_by_index) {
  const std::vector<std::size_t> order = largest_first({3, 10, 3, 0, 10, 7});
  BOOST_TEST(order == (std::vector<std::size_t>{1, 4, 5, 0, 2, 3}), boost::test_tools::per_element());
  BOOST_TEST(largest_first({}).empty());
  // Handed out in that order, the first failing item in it is the one reported.
  const std::vector<double> cost = {1, 5, 2, 9};
  const auto by_cost = largest_first(cost);
  for (unsigned threads : {1u, 2u}) {
    try {
      parallel_for(by_cost.size(), [&](std::size_t j) {
        if (by_cost[j] == 0 || by_cost[j] == 1) throw std::runtime_error("item " + std::to_string(by_cost[j]));
      }, threads);
      BOOST_FAIL("no exception");
    } catch (const std::runtime_error& e) {
      BOOST_TEST(std::string(e.what()) == "item 1");
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
