// Rank statistics against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/eval/ranking.h"

using namespace meshnbv::eval;

TEST(Ranking, AverageRanksShareTies) {
  EXPECT_EQ(average_ranks({10, 30, 20}), (std::vector<double>{1, 3, 2}));
  // 5 and 5 take ranks 2 and 3: both 2.5.
  EXPECT_EQ(average_ranks({1, 5, 5, 9}), (std::vector<double>{1, 2.5, 2.5, 4}));
}

TEST(Ranking, SpearmanOfMonotoneAndReversedOrders) {
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {10, 20, 30, 1000}), 1.0);
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
  // Ranks (1,2,3,4) against (2,1,4,3): 1 - 6 * 4 / (4 * 15) = 0.6.
  EXPECT_NEAR(spearman({1, 2, 3, 4}, {2, 1, 4, 3}), 0.6, 1e-12);
}

TEST(Ranking, SpearmanIsUndefinedForConstantOrTooShortLists) {
  EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3})));
  EXPECT_TRUE(std::isnan(spearman({1}, {2})));
  EXPECT_THROW(spearman({1, 2}, {1}), meshnbv::Error);
}

TEST(Ranking, RocAucPerfectRandomAndTied) {
  EXPECT_DOUBLE_EQ(roc_auc({0.1, 0.2, 0.8, 0.9}, {false, false, true, true}), 1.0);
  EXPECT_DOUBLE_EQ(roc_auc({0.1, 0.2, 0.8, 0.9}, {true, true, false, false}), 0.0);
  // One positive above one negative and below the other: 1/2.
  EXPECT_DOUBLE_EQ(roc_auc({0.1, 0.5, 0.9}, {false, true, false}), 0.5);
  // A tie between a positive and a negative counts one half.
  EXPECT_DOUBLE_EQ(roc_auc({0.5, 0.5}, {true, false}), 0.5);
  EXPECT_TRUE(std::isnan(roc_auc({0.1, 0.2}, {true, true})));
}
