// The SVG chart frame of the reports.
#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "report_output.h"

namespace quadra {

PlotAxis PlotAxis::logarithmicAround(double min, double max, double smallest, std::string label) {
  PlotAxis axis;
  axis.logarithmic = true;
  axis.smallest = smallest;
  axis.label = std::move(label);
  const double lo = std::floor(std::log10(std::max(min, smallest)));
  const double hi = std::ceil(std::log10(std::max(max, smallest) * 1.0001));
  axis.lo = std::pow(10.0, lo);
  axis.hi = std::pow(10.0, std::max(hi, lo + 1.0));
  return axis;
}

PlotAxis PlotAxis::linearAround(double min, double max, std::string label) {
  PlotAxis axis;
  axis.label = std::move(label);
  if (!(max > min)) {
    min -= 0.5;
    max += 0.5;
  }
  const double span = max - min;
  double step = std::pow(10.0, std::floor(std::log10(span)));
  for (const double factor : {0.1, 0.2, 0.5, 1.0})
    if (span / (step * factor) <= 10.0) {
      step *= factor;
      break;
    }
  axis.step = step;
  axis.lo = std::floor(min / step) * step;
  axis.hi = std::ceil(max / step) * step;
  return axis;
}

double PlotAxis::fraction(double value) const {
  if (!logarithmic) return (value - lo) / (hi - lo);
  return (std::log10(std::max(value, smallest)) - std::log10(lo)) /
         (std::log10(hi) - std::log10(lo));
}

std::vector<PlotAxis::Tick> PlotAxis::ticks() const {
  std::vector<Tick> ticks;
  if (!logarithmic) {
    const int count = int(std::lround((hi - lo) / step));
    for (int i = 0; i <= count; ++i) ticks.push_back({lo + step * i, true});
    return ticks;
  }
  const double lastDecade = std::log10(hi);
  for (double d = std::log10(lo); d <= lastDecade + 1e-9; d += 1)
    for (const int m : {1, 2, 5}) {
      const double value = m * std::pow(10.0, d);
      if (std::log10(value) > lastDecade + 1e-9) break;
      ticks.push_back({value, m == 1});
    }
  return ticks;
}

std::string SvgPlot::begin(const std::string& title, const std::string& subtitle) const {
  std::ostringstream svg;
  const double plotMiddleX = (left + width - right) / 2;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"13\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << plotMiddleX << "\" y=\"22\" text-anchor=\"middle\" font-size=\"16\">"
      << svgEscaped(title) << "</text>\n"
      << "<text x=\"" << plotMiddleX << "\" y=\"40\" text-anchor=\"middle\" fill=\"#555\">"
      << svgEscaped(subtitle) << "</text>\n";
  for (const PlotAxis::Tick& tick : x.ticks()) {
    const double at = toX(tick.value);
    svg << "<line x1=\"" << at << "\" y1=\"" << top << "\" x2=\"" << at << "\" y2=\""
        << height - bottom << "\" stroke=\"" << (tick.major ? "#bbb" : "#eee") << "\"/>\n"
        << "<text x=\"" << at << "\" y=\"" << height - bottom + 18 << "\" text-anchor=\"middle\">"
        << format("%g", tick.value) << "</text>\n";
  }
  for (const PlotAxis::Tick& tick : y.ticks()) {
    const double at = toY(tick.value);
    svg << "<line x1=\"" << left << "\" y1=\"" << at << "\" x2=\"" << width - right << "\" y2=\""
        << at << "\" stroke=\"" << (tick.major ? "#bbb" : "#eee") << "\"/>\n"
        << "<text x=\"" << left - 6 << "\" y=\"" << at + 4 << "\" text-anchor=\"end\">"
        << format("%g", tick.value) << "</text>\n";
  }
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << width - left - right
      << "\" height=\"" << height - top - bottom << "\" fill=\"none\" stroke=\"black\"/>\n"
      << "<text x=\"" << plotMiddleX << "\" y=\"" << height - 18 << "\" text-anchor=\"middle\">"
      << svgEscaped(x.label) << "</text>\n"
      << "<text transform=\"translate(20," << (top + height - bottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << svgEscaped(y.label) << "</text>\n";
  return svg.str();
}

std::string svgEscaped(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '&':
        escaped += "&amp;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

}  // namespace quadra
