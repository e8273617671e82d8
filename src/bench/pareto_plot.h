// Error-against-time plots for `shellmarch bench accuracy`: one log-log panel per mesh, every
// rung a dot with its label, the Pareto front (no other rung both faster and more accurate)
// ringed and joined. Drawn on the CPU into a PNG with the viewer's bitmap font: no plotting
// library needed.
#pragma once

#include <string>
#include <vector>

namespace sm::app::bench {

struct PlotPoint {
  std::string tag;    // a few characters beside the dot
  std::string label;  // the legend's line for the tag
  double ms = 0;      // time per frame (x)
  double error = 0;   // RMSE against the reference (y)
};

struct PlotPanel {
  std::string title;
  std::vector<PlotPoint> points;
};

// Indices of the points no other point dominates (at most as slow and as wrong, better in one).
std::vector<size_t> paretoFront(const std::vector<PlotPoint>& points);

// Panels in rows of `columns`.
void writeParetoPlot(const std::string& path, const std::vector<PlotPanel>& panels, int columns);

// The same plot drawn by matplotlib (pareto_plot.py beside the tool, run by `python`): labelled
// axes with units, log scales where values span decades, a legend; where Python or matplotlib is
// missing, writeParetoPlot's with one warning. Returns "matplotlib" or "built-in".
std::string writeErrorTimePlot(const std::string& path, const std::vector<PlotPanel>& panels,
                               int columns, const std::string& python);

}  // namespace sm::app::bench
