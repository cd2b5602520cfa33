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
// '$DATA'), then renders DIR/NAME.svg and DIR/NAME.png.
void render_chart(const std::string& dir, const std::string& name, const std::vector<DataBlock>& blocks,
                  const std::string& body);

// Quotes a string for a gnuplot script ('...' with '' for a quote).
std::string gp_quote(const std::string& text);

}  // namespace rastercmp::experiments
