// Point labels that do not pile up: points that would sit within a label's height and width of
// each other on the chart share one label listing their numbers ("4,5,9"). Pure function over
// data coordinates; the chart's axes (log x or not, ranges) decide what "close" means.
#pragma once

#include <string>
#include <vector>

namespace rastercmp::experiments {

struct ChartPoint {
  double x = 0, y = 0;
  int number = 0;  // the point's number in the chart's table
};

struct LabelCluster {
  double x = 0, y = 0;  // where the label goes: the cluster's leftmost point
  std::string text;     // the numbers of its points, ascending, comma-separated
};

struct ChartAxes {
  bool log_x = false;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
};

// Every point starts its own label; labels that would touch — rows within `near_y` of the plot
// height, spans from half of `near_x` (a fraction of the plot width) left of the leftmost point
// to half of it right of the text's end — merge, until none touch. Labels come out in the order of their first point;
// each lists its numbers in ascending order and sits at its leftmost point.
std::vector<LabelCluster> cluster_labels(const std::vector<ChartPoint>& points, const ChartAxes& axes,
                                         double near_x = 0.05, double near_y = 0.04);

}  // namespace rastercmp::experiments
