// Charts through gnuplot: one script per chart, rendered to SVG and PNG (pngcairo). Every file is
// written under a temporary name and renamed. A missing gnuplot is an EnvironmentError.
#pragma once

#include <string>
#include <vector>

namespace rastercmp::experiments {

// $RASTERCMP_GNUPLOT, else gnuplot on $PATH. Throws EnvironmentError when there is none.
std::string find_gnuplot();

// A whitespace-separated data block; gnuplot's `index N` picks block N.
struct DataBlock {
  std::string title;  // written as a comment line and used as the series title
  std::vector<std::vector<std::string>> rows;
};

// Writes DIR/NAME.dat (blocks separated by two blank lines), DIR/NAME.gp (the body, which reads
// '$DATA'), then renders DIR/NAME.svg and DIR/NAME.png. The script starts with the key set
// noenhanced and kSeriesStyles line types (distinct colour, dash and point type each; series i of
// a `plot for` gets line type i+1 by itself), and every title and label of the body is made
// noenhanced (noenhanced_text), so names such as near_coplanar print as written. Tic formats
// such as '10^{%L}' stay enhanced.
void render_chart(const std::string& dir, const std::string& name, const std::vector<DataBlock>& blocks,
                  const std::string& body);

inline constexpr int kSeriesStyles = 16;

// As render_chart, with the PNG `width` x `height` pixels (the SVG 0.8 times that), for a chart
// whose rows need more room than render_chart's 1200 x 800 (chart summary).
void render_chart_sized(const std::string& dir, const std::string& name, const std::vector<DataBlock>& blocks,
                        const std::string& body, int width, int height);

// The body with " noenhanced" added to each set title / xlabel / ylabel / cblabel / label line.
std::string noenhanced_text(const std::string& body);

// Zero on a log axis: gnuplot drops it without a word, so charts draw it at this floor (a decade
// below the smallest positive value; 0.1 when there is none) with a tic labelled "0".
double log_axis_floor(const std::vector<double>& values);
std::string zero_tic_command(const std::string& axis, double floor);  // "set xtics add ('0' F)"

// A symmetric log axis for parameters that include 0 or negative values (w -> 0 -> -1e-6): a value
// x is drawn at sign(x) (1 + log10(|x| / c)) when |x| >= c and at x / c below, with c the smallest
// non-zero |x|, so 0 sits at 0 with a tic labelled "0" and every value at its real place on the
// scale (one unit per decade), never at an equally spaced category.
struct SymlogAxis {
  double c = 1;
  explicit SymlogAxis(const std::vector<double>& values);
  double position(double x) const;
  // "set xtics (...)" with a tic at each value (labelled as written) and at 0 when one is 0.
  std::string tics_command(const std::string& axis, const std::vector<std::string>& labels) const;
};

// True when every number in column `column` of the blocks' rows is 0 or NaN and at least one is 0
// (rows whose cell is not a number, such as a header, are skipped): such a chart would be a flat
// line at 0, and the page shows a table instead.
bool only_zeros(const std::vector<DataBlock>& blocks, size_t column);

// Quotes a string for a gnuplot script ('...' with '' for a quote).
std::string gp_quote(const std::string& text);

}  // namespace rastercmp::experiments
