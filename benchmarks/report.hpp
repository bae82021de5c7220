#pragma once
// Error-against-run-time reports: one row per (data set, method), written as a Markdown table, a
// CSV file and an SVG plot (error on the y axis, time on a log x axis, one series per method
// family, the Pareto front of each data set marked).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpr_bench {

/// One measured method on one data set.
struct ReportRow {
  std::string dataset; ///< e.g. "gallery G (cross-slit)" or "chess leave-one-out"
  std::string series;  ///< method family, one plot series, e.g. "synthetic aperture"
  std::string method;  ///< full method description, e.g. "SA 7x7 cams 320x240"
  double build_s = 0;  ///< one-off preparation time (BVH, virtual camera array), seconds
  double render_s = 0; ///< render time per view, seconds (median)
  double rmse = 0;     ///< 8-bit code units
  double psnr = 0;     ///< dB
  double p99 = 0;      ///< 99th percentile per-pixel error, 8-bit code units
  std::string scalar = "float";
};

/// Indices of the rows of `rows` on the Pareto front of (render time, PSNR) within their data
/// set: no other row of that data set is at least as fast and at least as accurate, and better in
/// one of the two.
inline std::vector<bool> pareto_front(const std::vector<ReportRow>& rows) {
  std::vector<bool> front(rows.size(), true);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows.size(); ++j) {
      if (i == j || rows[i].dataset != rows[j].dataset) continue;
      const bool no_worse = rows[j].render_s <= rows[i].render_s && rows[j].psnr >= rows[i].psnr;
      const bool better = rows[j].render_s < rows[i].render_s || rows[j].psnr > rows[i].psnr;
      if (no_worse && better) {
        front[i] = false;
        break;
      }
    }
  return front;
}

inline std::string format_number(double v, const char* format = "%.3g") {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

inline void write_csv(const std::string& path, const std::vector<ReportRow>& rows) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  const std::vector<bool> front = pareto_front(rows);
  out << "dataset,series,method,scalar,build_s,render_s,rmse,psnr_db,p99,pareto\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ReportRow& r = rows[i];
    out << '"' << r.dataset << "\",\"" << r.series << "\",\"" << r.method << "\"," << r.scalar << ','
        << format_number(r.build_s, "%.6g") << ',' << format_number(r.render_s, "%.6g") << ','
        << format_number(r.rmse, "%.6g") << ',' << format_number(r.psnr, "%.6g") << ',' << format_number(r.p99, "%.6g")
        << ',' << (front[i] ? 1 : 0) << '\n';
  }
}

inline std::string markdown_table(const std::vector<ReportRow>& rows) {
  const std::vector<bool> front = pareto_front(rows);
  std::string t = "| data set | method | scalar | build (ms) | render (ms) | RMSE | PSNR (dB) | p99 | Pareto |\n"
                  "|---|---|---|---:|---:|---:|---:|---:|:---:|\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ReportRow& r = rows[i];
    t += "| " + r.dataset + " | " + r.method + " | " + r.scalar + " | " + format_number(r.build_s * 1e3, "%.1f") +
         " | " + format_number(r.render_s * 1e3, "%.2f") + " | " + format_number(r.rmse, "%.2f") + " | " +
         format_number(r.psnr, "%.2f") + " | " + format_number(r.p99, "%.1f") + " | " + (front[i] ? "*" : "") + " |\n";
  }
  return t;
}

/// SVG scatter plot of PSNR against render time (log axis), one colour per series, one panel per
/// data set stacked vertically; Pareto-front points are ringed and joined.
inline void write_svg(const std::string& path, const std::vector<ReportRow>& rows, const std::string& title) {
  std::vector<std::string> datasets, series;
  for (const ReportRow& r : rows) {
    if (std::find(datasets.begin(), datasets.end(), r.dataset) == datasets.end()) datasets.push_back(r.dataset);
    if (std::find(series.begin(), series.end(), r.series) == series.end()) series.push_back(r.series);
  }
  const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"};
  const std::vector<bool> front = pareto_front(rows);
  const double panel_w = 640, panel_h = 260, left = 70, top = 50, gap = 60, legend_w = 220;
  const double height = top + static_cast<double>(datasets.size()) * (panel_h + gap) + 20;
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << left + panel_w + legend_w << "' height='" << height
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << left << "' y='24' font-size='16'>" << title << "</text>\n";
  for (std::size_t s = 0; s < series.size(); ++s) {
    const double ly = top + 20 * static_cast<double>(s);
    out << "<circle cx='" << left + panel_w + 30 << "' cy='" << ly << "' r='5' fill='" << palette[s % 8] << "'/>"
        << "<text x='" << left + panel_w + 42 << "' y='" << ly + 4 << "'>" << series[s] << "</text>\n";
  }
  out << "<text x='" << left + panel_w + 30 << "' y='" << top + 20 * static_cast<double>(series.size()) + 10
      << "'>ringed + line: Pareto front</text>\n";
  for (std::size_t d = 0; d < datasets.size(); ++d) {
    const double y0 = top + static_cast<double>(d) * (panel_h + gap);
    double tmin = 1e300, tmax = 0, pmin = 1e300, pmax = -1e300;
    for (const ReportRow& r : rows)
      if (r.dataset == datasets[d] && r.render_s > 0 && std::isfinite(r.psnr)) {
        tmin = std::min(tmin, r.render_s), tmax = std::max(tmax, r.render_s);
        pmin = std::min(pmin, r.psnr), pmax = std::max(pmax, r.psnr);
      }
    if (tmax <= 0) continue;
    const double lt0 = std::floor(std::log10(tmin)), lt1 = std::max(lt0 + 1, std::ceil(std::log10(tmax)));
    pmin = std::floor(pmin / 5) * 5, pmax = std::max(pmin + 5, std::ceil(pmax / 5) * 5);
    const auto px = [&](double t) { return left + (std::log10(t) - lt0) / (lt1 - lt0) * panel_w; };
    const auto py = [&](double p) { return y0 + panel_h - (p - pmin) / (pmax - pmin) * panel_h; };
    out << "<rect x='" << left << "' y='" << y0 << "' width='" << panel_w << "' height='" << panel_h
        << "' fill='none' stroke='#444'/>\n<text x='" << left << "' y='" << y0 - 8 << "' font-weight='bold'>"
        << datasets[d] << "</text>\n";
    for (double e = lt0; e <= lt1; ++e)
      out << "<line x1='" << px(std::pow(10, e)) << "' y1='" << y0 << "' x2='" << px(std::pow(10, e)) << "' y2='"
          << y0 + panel_h << "' stroke='#ddd'/><text x='" << px(std::pow(10, e)) - 14 << "' y='" << y0 + panel_h + 16
          << "'>" << format_number(std::pow(10, e) * 1e3, "%g") << " ms</text>\n";
    for (double p = pmin; p <= pmax; p += 5)
      out << "<line x1='" << left << "' y1='" << py(p) << "' x2='" << left + panel_w << "' y2='" << py(p)
          << "' stroke='#eee'/><text x='" << left - 40 << "' y='" << py(p) + 4 << "'>" << p << " dB</text>\n";
    out << "<text x='" << left + panel_w / 2 - 60 << "' y='" << y0 + panel_h + 34
        << "'>render time per view (log)</text>\n";
    std::vector<std::pair<double, double>> front_points;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const ReportRow& r = rows[i];
      if (r.dataset != datasets[d] || !(r.render_s > 0) || !std::isfinite(r.psnr)) continue;
      const std::size_t s =
          static_cast<std::size_t>(std::find(series.begin(), series.end(), r.series) - series.begin());
      out << "<circle cx='" << px(r.render_s) << "' cy='" << py(r.psnr) << "' r='4' fill='" << palette[s % 8]
          << "'><title>" << r.method << ": " << format_number(r.psnr, "%.2f") << " dB, "
          << format_number(r.render_s * 1e3, "%.2f") << " ms</title></circle>\n";
      if (front[i]) {
        out << "<circle cx='" << px(r.render_s) << "' cy='" << py(r.psnr) << "' r='8' fill='none' stroke='black'/>\n";
        front_points.emplace_back(px(r.render_s), py(r.psnr));
      }
    }
    std::sort(front_points.begin(), front_points.end());
    if (front_points.size() > 1) {
      out << "<polyline fill='none' stroke='black' stroke-dasharray='4 3' points='";
      for (const auto& [x, y] : front_points) out << x << ',' << y << ' ';
      out << "'/>\n";
    }
  }
  out << "</svg>\n";
}

} // namespace mpr_bench
