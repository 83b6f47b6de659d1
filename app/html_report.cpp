#include "app/html_report.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/html_report_assets.h"

namespace svgf::app {
namespace {

// Series colours (matplotlib's tab10, first eight), in the order of a plot's series.
const char* const kSeriesColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                      "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"};

// A plot's SVG geometry (user units; the SVG is drawn at this size).
constexpr double kPlotWidth = 520, kPlotHeight = 200;
constexpr double kLeft = 62, kRight = 12, kTop = 10, kBottom = 30;

std::string number(double v, int digits = 4) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// Fixed two decimals: SVG coordinates.
std::string coord(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

// The value a plot draws for v: log10 on a log scale; NaN where nothing is drawn.
double plotted(double v, bool log_scale) {
  if (!std::isfinite(v)) return NAN;
  if (log_scale) return v > 0 ? std::log10(v) : NAN;
  return v;
}

double frame_x(int k, int frames) {
  const double width = kPlotWidth - kLeft - kRight;
  return frames <= 1 ? kLeft + width / 2 : kLeft + width * k / (frames - 1);
}

// One plot: axes with three labelled levels, a polyline per run of drawable values (a run of
// one value is a dot), the selected frame's cursor (moved by the script).
std::string svg_plot(const HtmlPlot& plot, const std::vector<std::string>& frames) {
  const int n = static_cast<int>(frames.size());
  // The values' range, widened by 5% on each side (or around a single value).
  double data_lo = INFINITY, data_hi = -INFINITY;
  for (const HtmlSeries& s : plot.series)
    for (double v : s.values)
      if (const double p = plotted(v, plot.log_scale); std::isfinite(p)) {
        data_lo = std::min(data_lo, p);
        data_hi = std::max(data_hi, p);
      }
  const double pad =
      data_hi > data_lo ? 0.05 * (data_hi - data_lo) : std::max(1e-9, 0.05 * std::fabs(data_lo));
  const double lo = data_lo - pad, hi = data_hi + pad;
  const double bottom = kPlotHeight - kBottom;
  auto y_of = [&](double p) { return bottom - (p - lo) / (hi - lo) * (bottom - kTop); };
  auto label_of = [&](double p) { return number(plot.log_scale ? std::pow(10.0, p) : p, 4); };

  std::ostringstream o;
  o << "<svg class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << kPlotWidth
    << ' ' << kPlotHeight << "\" width=\"" << kPlotWidth << "\" height=\"" << kPlotHeight
    << "\" data-frames=\"" << n << "\" data-x0=\"" << coord(frame_x(0, n)) << "\" data-x1=\""
    << coord(frame_x(n - 1, n)) << "\" role=\"img\" aria-label=\"" << html_escape(plot.title)
    << "\">\n";
  o << "<rect class=\"area\" x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\""
    << kPlotWidth - kLeft - kRight << "\" height=\"" << bottom - kTop << "\"/>\n";
  for (int level = 0; level < 3; ++level) {  // the lowest value, the middle, the highest
    const double p = data_lo + (data_hi - data_lo) * level / 2.0;
    const double y = y_of(p);
    o << "<line class=\"grid\" x1=\"" << kLeft << "\" x2=\"" << kPlotWidth - kRight << "\" y1=\""
      << coord(y) << "\" y2=\"" << coord(y) << "\"/><text class=\"tick\" x=\"" << kLeft - 4
      << "\" y=\"" << coord(y + 4) << "\" text-anchor=\"end\">" << label_of(p) << "</text>\n";
    if (data_hi == data_lo) break;  // one level: all values equal
  }
  o << "<text class=\"tick\" x=\"" << kLeft << "\" y=\"" << kPlotHeight - 10 << "\">"
    << html_escape(frames.front()) << "</text>\n";
  if (n > 1)
    o << "<text class=\"tick\" x=\"" << kPlotWidth - kRight << "\" y=\"" << kPlotHeight - 10
      << "\" text-anchor=\"end\">" << html_escape(frames.back()) << "</text>\n";
  o << "<line class=\"cursor\" x1=\"" << coord(frame_x(0, n)) << "\" x2=\"" << coord(frame_x(0, n))
    << "\" y1=\"" << kTop << "\" y2=\"" << bottom << "\"/>\n";
  for (size_t s = 0; s < plot.series.size(); ++s) {
    const HtmlSeries& series = plot.series[s];
    const char* colour = kSeriesColours[s % std::size(kSeriesColours)];
    std::vector<std::pair<double, double>> run;
    auto flush = [&] {
      if (run.size() == 1)
        o << "<circle class=\"point\" cx=\"" << coord(run[0].first) << "\" cy=\""
          << coord(run[0].second) << "\" r=\"2.5\" fill=\"" << colour << "\" data-series=\""
          << html_escape(series.name) << "\"/>\n";
      if (run.size() > 1) {
        o << "<polyline fill=\"none\" stroke=\"" << colour << "\" data-series=\""
          << html_escape(series.name) << "\" points=\"";
        for (size_t i = 0; i < run.size(); ++i)
          o << (i ? " " : "") << coord(run[i].first) << ',' << coord(run[i].second);
        o << "\"/>\n";
      }
      run.clear();
    };
    for (int k = 0; k < n; ++k) {
      const double p = plotted(series.values[static_cast<size_t>(k)], plot.log_scale);
      if (std::isfinite(p))
        run.emplace_back(frame_x(k, n), y_of(p));
      else
        flush();
    }
    flush();
  }
  o << "</svg>";
  return o.str();
}

bool drawable(const HtmlPlot& plot) {
  for (const HtmlSeries& s : plot.series)
    for (double v : s.values)
      if (std::isfinite(plotted(v, plot.log_scale))) return true;
  return false;
}

std::string plot_figure(const HtmlPlot& plot, const std::vector<std::string>& frames) {
  std::ostringstream o;
  o << "<figure class=\"plot-box\"><figcaption><b>" << html_escape(plot.title) << "</b>"
    << (plot.log_scale ? " <i>log scale</i>" : "");
  for (size_t s = 0; s < plot.series.size(); ++s)
    o << " <span class=\"key\"><span class=\"swatch\" style=\"background:"
      << kSeriesColours[s % std::size(kSeriesColours)] << "\"></span>"
      << html_escape(plot.series[s].name) << "</span>";
  o << "</figcaption>\n" << svg_plot(plot, frames) << "</figure>\n";
  return o.str();
}

std::string frame_images(const std::vector<HtmlImage>& images, int k, const std::string& note) {
  std::ostringstream o;
  o << "<div class=\"frame\" data-frame=\"" << k << "\"" << (k ? " hidden" : "") << ">";
  if (images.empty())
    o << "<p class=\"none\">No images embedded for this frame. " << html_escape(note) << "</p>";
  for (const HtmlImage& im : images)
    o << "<figure><img data-name=\"" << html_escape(im.name) << "\" alt=\"" << html_escape(im.name)
      << "\" src=\"data:image/png;base64," << base64(im.png) << "\"><figcaption>"
      << html_escape(im.name) << "</figcaption></figure>";
  o << "</div>\n";
  return o.str();
}

std::string colour_bar(const HtmlColourBar& bar) {
  if (bar.colours.empty()) return "";
  std::ostringstream o;
  o << "<div class=\"colour-bar\"><span>" << html_escape(bar.label)
    << ": 0</span><span class=\"bar\" "
    << "style=\"background:linear-gradient(to right";
  for (const std::string& c : bar.colours) o << ',' << html_escape(c);
  o << ")\"></span><span>1</span></div>\n";
  return o.str();
}

std::string table(const HtmlTable& t) {
  std::ostringstream o;
  o << "<table><caption>" << html_escape(t.title) << "</caption>\n";
  for (const auto& [name, value] : t.rows)
    o << "<tr><th>" << html_escape(name) << "</th><td>" << html_escape(value) << "</td></tr>\n";
  o << "</table>\n";
  return o.str();
}

// The numbers the script shows for the selected frame (null where there is none).
std::string data_json(const HtmlReport& r) {
  nlohmann::json j;
  j["frames"] = r.frames;
  j["plots"] = nlohmann::json::array();
  for (const HtmlPlot& p : r.plots) {
    if (!drawable(p)) continue;  // left out of the page
    nlohmann::json plot{{"title", p.title}, {"series", nlohmann::json::array()}};
    for (const HtmlSeries& s : p.series) {
      nlohmann::json values = nlohmann::json::array();
      for (double v : s.values) values.push_back(std::isfinite(v) ? nlohmann::json(v) : nullptr);
      plot["series"].push_back({{"name", s.name}, {"values", values}});
    }
    j["plots"].push_back(plot);
  }
  // Inside <script>: "</" would end the element early; "<\/" is the same JSON string.
  std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
    text.replace(at, 2, "<\\/");
  return text;
}

}  // namespace

std::string base64(const std::string& bytes) {
  static const char* const kDigits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 |
                       uint8_t(bytes[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out += kDigits[(v >> s) & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const uint32_t v =
        uint32_t(uint8_t(bytes[i])) << 16 | (two ? uint32_t(uint8_t(bytes[i + 1])) << 8 : 0);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += two ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

bool html_frame_has_images(int position, int frames) {
  if (position < 0 || position >= frames) return false;
  if (frames <= kHtmlMaxImageFrames) return true;
  const auto bucket = [&](int k) { return static_cast<int64_t>(k) * kHtmlMaxImageFrames / frames; };
  return position == 0 || bucket(position) != bucket(position - 1);
}

std::string html_images_note(int frames) {
  if (frames <= kHtmlMaxImageFrames) return "";
  return "Images are embedded for " + std::to_string(kHtmlMaxImageFrames) + " of the " +
         std::to_string(frames) + " frames, evenly spaced from the first (at most " +
         std::to_string(kHtmlMaxImageFrames) +
         " per page, to keep it small); the plots cover every frame.";
}

std::string html_report(const HtmlReport& r) {
  const size_t n = r.frames.size();
  if (n == 0) throw std::invalid_argument("html_report: no frames");
  if (!r.images.empty() && r.images.size() != n)
    throw std::invalid_argument("html_report: images for " + std::to_string(r.images.size()) +
                                " frames, " + std::to_string(n) + " frames");
  for (const HtmlPlot& p : r.plots)
    for (const HtmlSeries& s : p.series)
      if (s.values.size() != n)
        throw std::invalid_argument("html_report: series '" + p.title + ", " + s.name + "' has " +
                                    std::to_string(s.values.size()) + " values for " +
                                    std::to_string(n) + " frames");
  // The wipe offers the names of the first frame that has images.
  std::vector<std::string> names;
  for (const auto& set : r.images)
    if (!set.empty()) {
      for (const HtmlImage& im : set) names.push_back(im.name);
      break;
    }

  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    // No network: images come from data: URIs, style and script are inline.
    << "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
       "style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n"
    << "<title>" << html_escape(r.title) << "</title>\n<style>" << kStyle
    << "</style>\n</head>\n<body>\n"
    << "<h1>" << html_escape(r.title) << "</h1>\n";
  if (!r.subtitle.empty()) o << "<p class=\"sub\">" << html_escape(r.subtitle) << "</p>\n";

  o << "<section id=\"viewer\">\n<div class=\"controls\"><button id=\"prev\" "
       "type=\"button\">&#9664;</button>"
    << "<input id=\"frame\" type=\"range\" min=\"0\" max=\"" << n - 1
    << "\" value=\"0\" aria-label=\"frame\">"
    << "<button id=\"next\" type=\"button\">&#9654;</button><span id=\"frame-label\">1 / " << n
    << ": " << html_escape(r.frames[0]) << "</span></div>\n";
  if (!r.images_note.empty()) o << "<p class=\"note\">" << html_escape(r.images_note) << "</p>\n";
  if (!names.empty()) {
    o << "<div class=\"frames\">\n";
    for (size_t k = 0; k < n; ++k)
      o << frame_images(r.images[k], static_cast<int>(k), r.images_note);
    o << "</div>\n" << colour_bar(r.colour_bar);
  }
  o << "<div class=\"row\">\n";
  if (!names.empty()) {
    auto options = [&](size_t selected) {
      std::string s;
      for (size_t i = 0; i < names.size(); ++i)
        s += "<option" + std::string(i == selected ? " selected" : "") + ">" +
             html_escape(names[i]) + "</option>";
      return s;
    };
    auto index_of = [&](const std::string& name, size_t fallback) {
      const auto it = std::find(names.begin(), names.end(), name);
      return it == names.end() ? fallback : static_cast<size_t>(it - names.begin());
    };
    const size_t a = index_of(r.wipe_left, 0),
                 b = index_of(r.wipe_right, std::min<size_t>(1, names.size() - 1));
    o << "<div id=\"wipe-panel\"><h2>Wipe</h2><div class=\"controls\">left <select "
         "id=\"wipe-left\">"
      << options(a) << "</select> right <select id=\"wipe-right\">" << options(b)
      << "</select></div>\n"
      << "<div class=\"wipe-box\"><img id=\"wipe-b\" alt=\"right image\"><img id=\"wipe-a\" "
         "alt=\"left image\"></div>\n"
      << "<input id=\"wipe\" type=\"range\" min=\"0\" max=\"100\" value=\"50\" aria-label=\"wipe "
         "position\"></div>\n";
  } else {
    o << "<input id=\"wipe\" type=\"hidden\" value=\"50\"><select id=\"wipe-left\" hidden></select>"
      << "<select id=\"wipe-right\" hidden></select><div id=\"wipe-panel\" hidden><img "
         "id=\"wipe-a\" alt=\"\">"
      << "<img id=\"wipe-b\" alt=\"\"></div>\n";
  }
  o << "<div><h2>This frame</h2><table id=\"frame-values\"></table></div>\n</div>\n</section>\n";

  o << "<section><h2>Per frame</h2>\n<div class=\"plots\">\n";
  for (const HtmlPlot& p : r.plots)
    if (drawable(p)) o << plot_figure(p, r.frames);
  o << "</div>\n</section>\n<section><h2>Run</h2>\n";
  for (const HtmlTable& t : r.tables) o << table(t);
  o << "</section>\n<script type=\"application/json\" id=\"report-data\">" << data_json(r)
    << "</script>\n<script>" << kScript << "</script>\n</body>\n</html>\n";
  return o.str();
}

}  // namespace svgf::app
