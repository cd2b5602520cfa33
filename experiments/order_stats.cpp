#include "experiments/order_stats.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rastercmp::experiments {

double binomial_half_cdf(size_t n, size_t k) {
  double sum = 0;
  for (size_t i = 0; i <= std::min(k, n); ++i)
    sum += std::exp(std::lgamma(double(n) + 1) - std::lgamma(double(i) + 1) - std::lgamma(double(n - i) + 1) -
                    double(n) * std::log(2.0));
  return std::min(sum, 1.0);
}

MedianCi median_ci(std::vector<double> values, double confidence) {
  if (!(confidence > 0 && confidence < 1)) throw std::invalid_argument("median_ci: confidence must lie in (0, 1)");
  MedianCi out;
  const size_t n = values.size();
  if (n == 0) return out;
  std::sort(values.begin(), values.end());
  out.median = n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
  const double tail = (1 - confidence) / 2;
  size_t k = 1;
  while (k + 1 <= (n + 1) / 2 && binomial_half_cdf(n, k) <= tail) ++k;  // P(B <= (k+1)-1) still small enough
  out.low_rank = k;
  out.high_rank = n + 1 - k;
  out.low = values[out.low_rank - 1];
  out.high = values[out.high_rank - 1];
  out.coverage = 1 - 2 * (k >= 1 ? binomial_half_cdf(n, k - 1) : 0.0);
  return out;
}

}  // namespace rastercmp::experiments
