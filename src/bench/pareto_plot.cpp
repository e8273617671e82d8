#include "bench/pareto_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/vec4.hpp>

#include <nlohmann/json.hpp>

#include "bench/bench_common.h"
#include "common/file_util.h"
#include "common/log.h"
#include "scene/bitmap_font.h"
#include "scene/image.h"

namespace sm::app::bench {

std::vector<size_t> paretoFront(const std::vector<PlotPoint>& points) {
  std::vector<size_t> front;
  for (size_t i = 0; i < points.size(); ++i) {
    bool dominated = false;
    for (size_t j = 0; j < points.size() && !dominated; ++j) {
      const PlotPoint &a = points[j], &b = points[i];
      dominated =
          j != i && a.ms <= b.ms && a.error <= b.error && (a.ms < b.ms || a.error < b.error);
    }
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(),
            [&](size_t a, size_t b) { return points[a].ms < points[b].ms; });
  return front;
}

namespace {

constexpr int kPanelW = 560, kPlotH = 330, kLeft = 70, kRight = 20, kTop = 34, kBottom = 46,
              kLegendLine = 11;
const glm::vec4 kInk(0.1f, 0.1f, 0.12f, 1.0f), kGrid(0.85f, 0.85f, 0.88f, 1.0f),
    kDot(0.15f, 0.35f, 0.75f, 1.0f), kFront(0.85f, 0.25f, 0.1f, 1.0f);

struct Canvas {
  scene::Image img;
  void set(int x, int y, glm::vec4 c) {
    if (x >= 0 && y >= 0 && x < img.width && y < img.height)
      img.pixels[size_t(y) * img.width + x] = c;
  }
  void line(int x0, int y0, int x1, int y1, glm::vec4 c, int thick = 1) {
    const int n = std::max(std::abs(x1 - x0), std::abs(y1 - y0)) + 1;
    for (int i = 0; i <= n; ++i) {
      const int x = x0 + (x1 - x0) * i / n, y = y0 + (y1 - y0) * i / n;
      for (int d = 0; d < thick; ++d) set(x + d % 2, y + d / 2, c);
    }
  }
  void disc(int cx, int cy, int r, glm::vec4 c, bool ring = false) {
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) {
        const int d2 = x * x + y * y;
        if (d2 <= r * r && (!ring || d2 >= (r - 2) * (r - 2))) set(cx + x, cy + y, c);
      }
  }
  // Text in the 5x7 font, `scale` pixels per dot, top-left at (x, y).
  void text(int x, int y, const std::string& s, glm::vec4 c, int scale = 1) {
    scene::drawText(s, x, y, scale, [&](int px, int py) { set(px, py, c); });
  }
};

std::string powerLabel(int e) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "1e%d", e);
  return buf;
}

int panelHeight(const PlotPanel& p) {
  return kPlotH + 8 + kLegendLine * int(p.points.size());
}

void drawPanel(Canvas& cv, int ox, int oy, const PlotPanel& p) {
  if (p.points.empty()) return;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& q : p.points) {
    x0 = std::min(x0, std::log10(std::max(q.ms, 1e-3)));
    x1 = std::max(x1, std::log10(std::max(q.ms, 1e-3)));
    y0 = std::min(y0, std::log10(std::max(q.error, 1e-9)));
    y1 = std::max(y1, std::log10(std::max(q.error, 1e-9)));
  }
  x0 = std::floor(x0 - 0.05), x1 = std::ceil(x1 + 0.05), y0 = std::floor(y0 - 0.05),
  y1 = std::ceil(y1 + 0.05);
  const int w = kPanelW - kLeft - kRight, h = kPlotH - kTop - kBottom;
  const int top = oy + kTop;
  auto px = [&](double ms) {
    return ox + kLeft + int((std::log10(std::max(ms, 1e-3)) - x0) / (x1 - x0) * w);
  };
  auto py = [&](double e) {
    return top + h - int((std::log10(std::max(e, 1e-9)) - y0) / (y1 - y0) * h);
  };
  for (int e = int(x0); e <= int(x1); ++e) {
    const int x = ox + kLeft + int((e - x0) / (x1 - x0) * w);
    cv.line(x, top, x, top + h, kGrid);
    cv.text(x - 9, top + h + 6, powerLabel(e), kInk);
  }
  for (int e = int(y0); e <= int(y1); ++e) {
    const int y = top + h - int((e - y0) / (y1 - y0) * h);
    cv.line(ox + kLeft, y, ox + kLeft + w, y, kGrid);
    cv.text(ox + 8, y - 3, powerLabel(e), kInk);
  }
  cv.line(ox + kLeft, top + h, ox + kLeft + w, top + h, kInk);
  cv.line(ox + kLeft, top, ox + kLeft, top + h, kInk);
  cv.text(ox + kLeft, oy + 10, p.title, kInk, 2);
  cv.text(ox + kLeft + w / 2 - 60, top + h + 22, "ms per frame", kInk);
  cv.text(ox + 8, top - 14, "RMSE", kInk);
  const std::vector<size_t> front = paretoFront(p.points);
  for (size_t k = 1; k < front.size(); ++k) {
    const PlotPoint &a = p.points[front[k - 1]], &b = p.points[front[k]];
    cv.line(px(a.ms), py(a.error), px(b.ms), py(b.error), kFront, 2);
  }
  for (size_t i = 0; i < p.points.size(); ++i) {
    const PlotPoint& q = p.points[i];
    const bool onFront = std::find(front.begin(), front.end(), i) != front.end();
    cv.disc(px(q.ms), py(q.error), 3, kDot);
    if (onFront) cv.disc(px(q.ms), py(q.error), 7, kFront, true);
    cv.text(px(q.ms) + 8, py(q.error) - 3, q.tag, onFront ? kFront : kInk);
    cv.text(ox + kLeft, oy + kPlotH + 8 + kLegendLine * int(i), q.tag + "  " + q.label,
            onFront ? kFront : kInk);
  }
}

}  // namespace

void writeParetoPlot(const std::string& path, const std::vector<PlotPanel>& panels, int columns) {
  columns = std::max(columns, 1);
  const int rows = (int(panels.size()) + columns - 1) / columns;
  std::vector<int> rowTop(size_t(rows) + 1, 0);
  for (int r = 0; r < rows; ++r) {
    int tallest = kPlotH;
    for (int c = 0; c < columns && r * columns + c < int(panels.size()); ++c)
      tallest = std::max(tallest, panelHeight(panels[size_t(r * columns + c)]));
    rowTop[size_t(r) + 1] = rowTop[size_t(r)] + tallest + 10;
  }
  Canvas cv;
  cv.img = scene::Image(kPanelW * std::min(columns, std::max(int(panels.size()), 1)),
                        std::max(rowTop.back(), 1));
  std::fill(cv.img.pixels.begin(), cv.img.pixels.end(), glm::vec4(1.0f));
  for (size_t i = 0; i < panels.size(); ++i)
    drawPanel(cv, int(i) % columns * kPanelW, rowTop[i / size_t(columns)], panels[i]);
  scene::writePng(path, cv.img, glm::vec3(1.0f));
}

std::string writeErrorTimePlot(const std::string& path, const std::vector<PlotPanel>& panels,
                               int columns, const std::string& python) {
  nlohmann::json j = nlohmann::json::array();
  for (const PlotPanel& p : panels) {
    nlohmann::json points = nlohmann::json::array();
    for (const PlotPoint& q : p.points)
      points.push_back({{"tag", q.tag}, {"label", q.label}, {"ms", q.ms}, {"error", q.error}});
    j.push_back({{"title", p.title}, {"points", points}, {"front", paretoFront(p.points)}});
  }
  const std::string panelsPath = path + ".panels.json", result = path + ".plot.json",
                    logPath = path + ".plot.log";
  writeJsonFile(panelsPath, j);
  std::remove(path.c_str());  // a plot of an earlier run is not this one
  const PeerRun run =
      runPeer({python,
               "pareto_plot.py",
               {"--panels", panelsPath, "--out", path, "--columns", std::to_string(columns)},
               result,
               logPath});
  for (const std::string& f : {panelsPath, result, logPath}) std::remove(f.c_str());
  if (run.ok && fileExists(path)) return "matplotlib";
  log::warning("plot ", path, ": matplotlib could not draw it (", run.error,
               "); drawing the built-in plot");
  writeParetoPlot(path, panels, columns);
  return "built-in";
}

}  // namespace sm::app::bench
