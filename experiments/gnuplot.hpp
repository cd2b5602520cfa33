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

// The body with " noenhanced" added to each set title / xlabel / ylabel / cblabel / label line.
std::string noenhanced_text(const std::string& body);

// Zero on a log axis: gnuplot drops it without a word, so charts draw it at this floor (a decade
// below the smallest positive value; 0.1 when there is none) with a tic labelled "0".
double log_axis_floor(const std::vector<double>& values);
std::string zero_tic_command(const std::string& axis, double floor);  // "set xtics add ('0' F)"

// Quotes a string for a gnuplot script ('...' with '' for a quote).
std::string gp_quote(const std::string& text);

}  // namespace rastercmp::experiments
