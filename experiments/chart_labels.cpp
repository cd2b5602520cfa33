#include "experiments/chart_labels.hpp"

#include <algorithm>
#include <cmath>

namespace rastercmp::experiments {
namespace {

// The width of one label character as a fraction of the plot width (a 9-point font on the
// 1200-pixel chart's plot area of about 700 pixels).
constexpr double kCharWidth = 0.011;

// A data position as a fraction of the plot area, 0..1 along each axis.
struct PlotFraction {
  double u = 0, v = 0;
};

PlotFraction to_fraction(double x, double y, const ChartAxes& axes) {
  const auto along = [](double value, double lo, double hi) { return hi > lo ? (value - lo) / (hi - lo) : 0.0; };
  const double u = axes.log_x ? along(std::log10(x), std::log10(axes.x_min), std::log10(axes.x_max))
                              : along(x, axes.x_min, axes.x_max);
  return {u, along(y, axes.y_min, axes.y_max)};
}

struct Cluster {
  PlotFraction anchor;  // the leftmost point's position
  double x = 0, y = 0;  // the same point in data coordinates
  std::vector<int> numbers;
};

std::string label_text(std::vector<int> numbers) {
  std::sort(numbers.begin(), numbers.end());
  std::string text;
  for (int n : numbers) {
    if (!text.empty()) text += ',';
    text += std::to_string(n);
  }
  return text;
}

// Two labels collide when their rows are within `near_y` and their spans [anchor - near_x / 2,
// anchor + near_x / 2 + width] overlap.
bool collide(const Cluster& a, const Cluster& b, double near_x, double near_y) {
  if (std::fabs(a.anchor.v - b.anchor.v) >= near_y) return false;
  const auto left = [&](const Cluster& c) { return c.anchor.u - near_x / 2; };
  const auto right = [&](const Cluster& c) {
    return c.anchor.u + near_x / 2 + kCharWidth * double(label_text(c.numbers).size());
  };
  return left(a) < right(b) && left(b) < right(a);
}

void merge_into(Cluster& into, const Cluster& from) {
  if (from.anchor.u < into.anchor.u) {
    into.anchor = from.anchor;
    into.x = from.x;
    into.y = from.y;
  }
  into.numbers.insert(into.numbers.end(), from.numbers.begin(), from.numbers.end());
}

}  // namespace

std::vector<LabelCluster> cluster_labels(const std::vector<ChartPoint>& points, const ChartAxes& axes, double near_x,
                                         double near_y) {
  std::vector<Cluster> clusters;
  for (const ChartPoint& point : points)
    clusters.push_back({to_fraction(point.x, point.y, axes), point.x, point.y, {point.number}});
  // Merge colliding labels until none collide; a merged label is longer, so repeat.
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t i = 0; i < clusters.size() && !merged; ++i)
      for (size_t j = i + 1; j < clusters.size() && !merged; ++j)
        if (collide(clusters[i], clusters[j], near_x, near_y)) {
          merge_into(clusters[i], clusters[j]);
          clusters.erase(clusters.begin() + std::ptrdiff_t(j));
          merged = true;
        }
  }
  std::vector<LabelCluster> labels;
  for (const Cluster& c : clusters) labels.push_back({c.x, c.y, label_text(c.numbers)});
  return labels;
}

}  // namespace rastercmp::experiments
