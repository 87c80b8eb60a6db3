// The frame of the reports' SVG charts (`quadra report textures`, `quadra
// report samples`): the canvas, a title, two axes with grid lines and tick
// labels, and the mapping from data to canvas coordinates. What is drawn
// inside the frame is each report's own.
#pragma once

#include <string>
#include <vector>

namespace quadra {

// One axis of a chart: the data range it spans and how values map onto it.
struct PlotAxis {
  double lo = 0.0, hi = 1.0;  // data values at the two ends
  bool logarithmic = false;
  std::string label;

  // Whole decades around [min, max], so grid lines land on round numbers;
  // values below `smallest` (zero, say) are drawn at it.
  static PlotAxis logarithmicAround(double min, double max, double smallest, std::string label);
  // Ends on multiples of a 1-2-5 step that gives four to ten intervals.
  static PlotAxis linearAround(double min, double max, std::string label);

  // Where a value lies along the axis, 0 at lo and 1 at hi (outside for values beyond).
  double fraction(double value) const;
  struct Tick {
    double value;
    bool major;  // a decade of a logarithmic axis; every tick of a linear one
  };
  // Logarithmic: 1, 2 and 5 times each power of ten; linear: every step.
  std::vector<Tick> ticks() const;

  double smallest = 0.0;  // logarithmic: the floor values are clamped to
  double step = 1.0;      // linear: the distance between ticks
};

struct SvgPlot {
  PlotAxis x, y;
  double width = 760, height = 520;
  double left = 80, right = 30, top = 50, bottom = 60;  // margins around the plot area

  double toX(double value) const { return left + x.fraction(value) * (width - left - right); }
  double toY(double value) const {
    return height - bottom - y.fraction(value) * (height - top - bottom);
  }
  // The document's opening: white canvas, title and subtitle, grid lines,
  // tick labels, the plot area's border and both axis labels.
  std::string begin(const std::string& title, const std::string& subtitle) const;
  static std::string end() { return "</svg>\n"; }
};

// Text made safe for SVG character data and attribute values.
std::string svgEscaped(const std::string& text);

}  // namespace quadra
