// The median of repeated timings and its distribution-free confidence interval from order
// statistics (issue 21 item 4). With n sorted values x(1) <= ... <= x(n), [x(k), x(n+1-k)] covers
// the true median with probability 1 - 2 P(B <= k-1), B ~ Binomial(n, 1/2), whatever the timing
// distribution; k is the largest rank that keeps that probability at or above the confidence asked
// for. Too few values for that (n < 6 at 95%): k = 1, the whole range, with its lower coverage.
#pragma once

#include <cstddef>
#include <vector>

namespace rastercmp::experiments {

struct MedianCi {
  double median = 0, low = 0, high = 0;
  double coverage = 0;      // the interval's actual coverage probability
  size_t low_rank = 0, high_rank = 0;  // 1-based ranks k and n+1-k; 0 for no values
};

// Throws std::invalid_argument for a confidence outside (0, 1). No values: all zero.
MedianCi median_ci(std::vector<double> values, double confidence = 0.95);

// P(B <= k) for B ~ Binomial(n, 1/2).
double binomial_half_cdf(size_t n, size_t k);

}  // namespace rastercmp::experiments
