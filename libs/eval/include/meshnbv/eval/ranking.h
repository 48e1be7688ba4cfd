// How well a score ranks a truth: the rank statistics the quality checks
// use (Spearman's rank correlation, ROC AUC), with ties handled.
#pragma once

#include <vector>

namespace meshnbv::eval {

// Average ranks (1-based), tied values sharing their mean rank.
std::vector<double> average_ranks(const std::vector<double>& values);

// Spearman's rank correlation of a and b (same length, >= 2): Pearson's
// correlation of their average ranks. NaN when either is constant.
double spearman(const std::vector<double>& a, const std::vector<double>& b);

// ROC AUC of `score` for the `positive` items, by the Mann-Whitney
// statistic (ties count one half). NaN without positives or negatives.
double roc_auc(const std::vector<double>& score, const std::vector<bool>& positive);

}  // namespace meshnbv::eval
