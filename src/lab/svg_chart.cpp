#include "lab/svg_chart.h"

#include "core/atomic_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace lab {

namespace {

constexpr const char* kPalette[kPaletteSize] = {
    "#0072B2", // blue
    "#D55E00", // vermillion
    "#009E73", // bluish green
    "#CC79A7", // reddish purple
    "#E69F00", // orange
    "#56B4E9", // sky blue
    "#000000", // black
    "#B8A000", // Okabe-Ito yellow (#F0E442) darkened: the original vanishes on white
    "#882255", // wine (Paul Tol's muted scheme): two more for the ten pendulum methods
    "#44AA99", // teal (Paul Tol's muted scheme)
};

constexpr int kTitleHeight = 40;
constexpr int kPlotLeft = 88;
constexpr int kLegendWidth = 230;
constexpr int kPlotTopInPanel = 52;
constexpr int kPlotBottomMargin = 56;
constexpr std::size_t kMaxMarkers = 400;

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

std::string escape(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
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
            out += "&apos;";
            break;
        default:
            // Control characters other than tab and newline are not allowed in XML 1.0 at all.
            if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
        }
    }
    return out;
}

// Greedy word wrap to lines of at most `width` characters (a longer word gets a line of its own);
// '\n' in the text forces a break.
std::vector<std::string> wrap(const std::string& text, std::size_t width) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string para = text.substr(start, end - start);
        std::string line, word;
        for (std::size_t i = 0; i <= para.size(); ++i) {
            if (i < para.size() && para[i] != ' ') {
                word += para[i];
                continue;
            }
            if (word.empty()) continue;
            if (!line.empty() && line.size() + 1 + word.size() > width) {
                lines.push_back(line);
                line.clear();
            }
            line += (line.empty() ? "" : " ") + word;
            word.clear();
        }
        if (!line.empty()) lines.push_back(line);
        start = end + 1;
    }
    return lines;
}

bool drawableOn(AxisScale kind, double v) { return std::isfinite(v) && (kind == AxisScale::Linear || v > 0.0); }

// One axis after its range is settled: maps data values to pixels and lists its ticks.
struct Scale {
    AxisScale kind = AxisScale::Linear;
    double lo = 0.0, hi = 1.0;       // in transformed units (log10 of the value for a log axis)
    double pixLo = 0.0, pixHi = 1.0; // pixel positions of lo and hi

    bool drawable(double v) const { return drawableOn(kind, v); }
    double transform(double v) const { return kind == AxisScale::Log10 ? std::log10(v) : v; }
    double toPixel(double v) const { return pixLo + (transform(v) - lo) / (hi - lo) * (pixHi - pixLo); }
};

struct Tick {
    double pixel;
    std::string label; // empty: a minor tick
};

double niceStep(double span, int targetTicks) {
    const double raw = span / targetTicks;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    const double f = raw / mag;
    const double nice = f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0;
    return nice * mag;
}

std::string linearLabel(double v, double step) {
    if (std::fabs(v) < step * 1e-9) v = 0.0; // no "-0" or "1.2e-17" at the origin
    char buf[48];
    const double mag = std::max(std::fabs(v), step);
    if (mag >= 1e6 || step < 1e-4) {
        std::snprintf(buf, sizeof buf, "%g", v);
    } else {
        const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
        std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    }
    return buf;
}

std::string decadeLabel(int k) {
    if (k >= -2 && k <= 3) {
        static constexpr const char* kPlain[] = {"0.01", "0.1", "1", "10", "100", "1000"};
        return kPlain[k + 2];
    }
    return "1e" + std::to_string(k);
}

// Settles the range of one axis from the fixed bounds or from the data values that can be drawn.
Scale settle(const Axis& axis, const std::vector<double>& values, double pixLo, double pixHi) {
    Scale s;
    s.kind = axis.scale;
    s.pixLo = pixLo;
    s.pixHi = pixHi;
    double vmin = INFINITY, vmax = -INFINITY;
    for (double v : values) {
        if (!s.drawable(v)) continue;
        vmin = std::min(vmin, v);
        vmax = std::max(vmax, v);
    }
    // A fixed bound that cannot be drawn on this axis (<= 0 on log, NaN) falls back to the data.
    if (axis.min && s.drawable(*axis.min)) vmin = *axis.min;
    if (axis.max && s.drawable(*axis.max)) vmax = *axis.max;
    const bool fixedBoth =
        axis.min && axis.max && s.drawable(*axis.min) && s.drawable(*axis.max) && *axis.min < *axis.max;

    if (!(vmin <= vmax)) { // no drawable data at all
        vmin = s.kind == AxisScale::Log10 ? 1.0 : 0.0;
        vmax = s.kind == AxisScale::Log10 ? 10.0 : 1.0;
    }
    if (s.kind == AxisScale::Log10) {
        s.lo = std::log10(vmin);
        s.hi = std::log10(vmax);
        if (!fixedBoth) {
            s.lo = std::floor(s.lo + 1e-9);
            s.hi = std::ceil(s.hi - 1e-9);
        }
        if (s.hi <= s.lo) s.hi = s.lo + 1.0;
    } else {
        if (vmax - vmin <= std::fabs(vmax) * 1e-12) { // one value: make a band around it
            const double pad = vmin == 0.0 ? 1.0 : std::fabs(vmin) * 0.1;
            vmin -= pad;
            vmax += pad;
        }
        s.lo = vmin;
        s.hi = vmax;
        if (!fixedBoth) {
            const double step = niceStep(vmax - vmin, 6);
            s.lo = std::floor(vmin / step + 1e-9) * step;
            s.hi = std::ceil(vmax / step - 1e-9) * step;
            if (s.hi <= s.lo) s.hi = s.lo + step;
        }
    }
    return s;
}

std::vector<Tick> ticks(const Scale& s) {
    std::vector<Tick> out;
    auto pix = [&](double t) { return s.pixLo + (t - s.lo) / (s.hi - s.lo) * (s.pixHi - s.pixLo); };
    if (s.kind == AxisScale::Log10) {
        const int first = static_cast<int>(std::ceil(s.lo - 1e-9));
        const int last = static_cast<int>(std::floor(s.hi + 1e-9));
        const int decades = last - first + 1;
        const int labelEvery = std::max(1, (decades + 8) / 9);
        for (int k = first; k <= last; ++k) {
            out.push_back({pix(k), (k - first) % labelEvery == 0 ? decadeLabel(k) : std::string()});
        }
        if (s.hi - s.lo <= 6.0) {
            for (int k = first - 1; k <= last; ++k) {
                for (int m = 2; m <= 9; ++m) {
                    const double t = k + std::log10(static_cast<double>(m));
                    if (t > s.lo + 1e-9 && t < s.hi - 1e-9) out.push_back({pix(t), std::string()});
                }
            }
        }
        if (first > last) { // a fixed range inside one decade: label its ends
            out.push_back({pix(s.lo), linearLabel(std::pow(10.0, s.lo), std::pow(10.0, s.lo) / 100)});
            out.push_back({pix(s.hi), linearLabel(std::pow(10.0, s.hi), std::pow(10.0, s.hi) / 100)});
        }
        return out;
    }
    const double step = niceStep(s.hi - s.lo, 6);
    for (double i = std::ceil(s.lo / step - 1e-9); i * step <= s.hi + step * 1e-9; i += 1.0) {
        out.push_back({pix(i * step), linearLabel(i * step, step)});
    }
    return out;
}

struct Point {
    double x, y;
};

// Liang-Barsky: clips the segment a-b to the rectangle; false when nothing of it is inside.
bool clipSegment(Point& a, Point& b, double x0, double y0, double x1, double y1) {
    double t0 = 0.0, t1 = 1.0;
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a.x - x0, x1 - a.x, a.y - y0, y1 - a.y};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return false;
            continue;
        }
        const double r = q[i] / p[i];
        if (p[i] < 0.0) {
            t0 = std::max(t0, r);
        } else {
            t1 = std::min(t1, r);
        }
        if (t0 > t1) return false;
    }
    // Unclipped ends stay bit-identical, so the next segment can tell that it continues this one.
    const Point start = t0 == 0.0 ? a : Point{a.x + t0 * dx, a.y + t0 * dy};
    const Point end = t1 == 1.0 ? b : Point{a.x + t1 * dx, a.y + t1 * dy};
    a = start;
    b = end;
    return true;
}

// Keeps, per pixel column of a run, the first, lowest, highest and last vertex in their original order:
// the drawn line is the same to the eye, the file a fraction of the size.
std::vector<Point> thin(const std::vector<Point>& run) {
    if (run.size() < 8) return run;
    std::vector<Point> out;
    std::size_t i = 0;
    while (i < run.size()) {
        const double column = std::floor(run[i].x);
        std::size_t j = i;
        std::size_t lo = i, hi = i;
        while (j + 1 < run.size() && std::floor(run[j + 1].x) == column) {
            ++j;
            if (run[j].y < run[lo].y) lo = j;
            if (run[j].y > run[hi].y) hi = j;
        }
        std::size_t keep[4] = {i, std::min(lo, hi), std::max(lo, hi), j};
        std::size_t prev = run.size();
        for (std::size_t k : keep) {
            if (k != prev) out.push_back(run[k]);
            prev = k;
        }
        i = j + 1;
    }
    return out;
}

std::string markerShape(int shape, double x, double y, const char* colour) {
    const double r = 3.5;
    std::string fill = std::string("fill=\"") + colour + "\" stroke=\"" + colour + "\"";
    switch (shape % kPaletteSize) {
    case 0:
        return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\" " + fill + "/>";
    case 1:
        return "<rect x=\"" + num(x - r) + "\" y=\"" + num(y - r) + "\" width=\"" + num(2 * r) + "\" height=\"" +
               num(2 * r) + "\" " + fill + "/>";
    case 2:
        return "<polygon points=\"" + num(x) + "," + num(y - r * 1.2) + " " + num(x + r * 1.1) + "," +
               num(y + r * 0.8) + " " + num(x - r * 1.1) + "," + num(y + r * 0.8) + "\" " + fill + "/>";
    case 3:
        return "<polygon points=\"" + num(x) + "," + num(y - r * 1.3) + " " + num(x + r * 1.3) + "," + num(y) + " " +
               num(x) + "," + num(y + r * 1.3) + " " + num(x - r * 1.3) + "," + num(y) + "\" " + fill + "/>";
    case 4:
        return "<polygon points=\"" + num(x) + "," + num(y + r * 1.2) + " " + num(x + r * 1.1) + "," +
               num(y - r * 0.8) + " " + num(x - r * 1.1) + "," + num(y - r * 0.8) + "\" " + fill + "/>";
    case 5:
        return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\" fill=\"white\" stroke=\"" +
               colour + "\" stroke-width=\"1.5\"/>";
    case 6:
        return "<path d=\"M" + num(x - r) + " " + num(y - r) + "L" + num(x + r) + " " + num(y + r) + "M" + num(x - r) +
               " " + num(y + r) + "L" + num(x + r) + " " + num(y - r) + "\" stroke=\"" + colour +
               "\" stroke-width=\"1.8\" fill=\"none\"/>";
    case 8: // open triangle
        return "<polygon points=\"" + num(x) + "," + num(y - r * 1.2) + " " + num(x + r * 1.1) + "," +
               num(y + r * 0.8) + " " + num(x - r * 1.1) + "," + num(y + r * 0.8) + "\" fill=\"white\" stroke=\"" +
               colour + "\" stroke-width=\"1.5\"/>";
    case 9: // open diamond
        return "<polygon points=\"" + num(x) + "," + num(y - r * 1.3) + " " + num(x + r * 1.3) + "," + num(y) + " " +
               num(x) + "," + num(y + r * 1.3) + " " + num(x - r * 1.3) + "," + num(y) + "\" fill=\"white\" stroke=\"" +
               colour + "\" stroke-width=\"1.5\"/>";
    default: // 7: open square
        return "<rect x=\"" + num(x - r) + "\" y=\"" + num(y - r) + "\" width=\"" + num(2 * r) + "\" height=\"" +
               num(2 * r) + "\" fill=\"white\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>";
    }
}

// True when the raster's cells fill its grid exactly: at least one cell, nx * ny of them.
bool rasterFits(const Raster& r) {
    return r.xEdges.size() >= 2 && r.yEdges.size() >= 2 &&
           r.cells.size() == (r.xEdges.size() - 1) * (r.yEdges.size() - 1);
}

// The raster's cells as rects, one per run of equal neighbouring cells in a row, clipped to the plot area.
void renderRaster(std::string& svg, const Raster& r, int index, const Scale& sx, const Scale& sy, double left,
                  double right, double plotTop, double plotBottom) {
    const std::size_t nx = r.xEdges.size() - 1, ny = r.yEdges.size() - 1;
    auto colourOf = [&](std::size_t row, std::size_t col) {
        const int c = r.cells[row * nx + col];
        const bool drawable = sx.drawable(r.xEdges[col]) && sx.drawable(r.xEdges[col + 1]);
        return c >= 0 && static_cast<std::size_t>(c) < r.colours.size() && drawable ? c : -1;
    };
    svg += "<g id=\"raster" + std::to_string(index) + "\" shape-rendering=\"crispEdges\">\n";
    for (std::size_t row = 0; row < ny; ++row) {
        if (!sy.drawable(r.yEdges[row]) || !sy.drawable(r.yEdges[row + 1])) continue;
        const double ya = sy.toPixel(r.yEdges[row]), yb = sy.toPixel(r.yEdges[row + 1]);
        const double y0 = std::clamp(std::min(ya, yb), plotTop, plotBottom);
        const double y1 = std::clamp(std::max(ya, yb), plotTop, plotBottom);
        if (!(y1 > y0)) continue; // outside the plot, or beyond what a double can place
        std::size_t col = 0;
        while (col < nx) {
            const int c = colourOf(row, col);
            std::size_t end = col + 1;
            while (end < nx && colourOf(row, end) == c) ++end;
            if (c >= 0) {
                const double xa = sx.toPixel(r.xEdges[col]), xb = sx.toPixel(r.xEdges[end]);
                const double x0 = std::clamp(std::min(xa, xb), left, right);
                const double x1 = std::clamp(std::max(xa, xb), left, right);
                if (x1 > x0) {
                    svg += "<rect x=\"" + num(x0) + "\" y=\"" + num(y0) + "\" width=\"" + num(x1 - x0) +
                           "\" height=\"" + num(y1 - y0) + "\" fill=\"" +
                           escape(r.colours[static_cast<std::size_t>(c)]) + "\"/>\n";
                }
            }
            col = end;
        }
    }
    svg += "</g>\n";
}

struct PlotBox {
    double left, right, top, bottom; // pixels
};

// The grid lines and ticks of both axes, under everything else.
void renderGrid(std::string& svg, const Scale& sx, const Scale& sy, const PlotBox& b) {
    const double left = b.left, right = b.right, plotTop = b.top, plotBottom = b.bottom;
    for (const Tick& t : ticks(sx)) {
        const bool major = !t.label.empty();
        svg += "<line x1=\"" + num(t.pixel) + "\" y1=\"" + num(plotTop) + "\" x2=\"" + num(t.pixel) + "\" y2=\"" +
               num(plotBottom) + "\" stroke=\"" + (major ? "#dddddd" : "#f0f0f0") + "\" stroke-width=\"1\"/>\n";
        svg += "<line x1=\"" + num(t.pixel) + "\" y1=\"" + num(plotBottom) + "\" x2=\"" + num(t.pixel) + "\" y2=\"" +
               num(plotBottom + (major ? 6 : 3)) + "\" stroke=\"#333333\"/>\n";
        if (major) {
            svg += "<text x=\"" + num(t.pixel) + "\" y=\"" + num(plotBottom + 20) +
                   "\" text-anchor=\"middle\" font-size=\"12\">" + escape(t.label) + "</text>\n";
        }
    }
    for (const Tick& t : ticks(sy)) {
        const bool major = !t.label.empty();
        svg += "<line x1=\"" + num(left) + "\" y1=\"" + num(t.pixel) + "\" x2=\"" + num(right) + "\" y2=\"" +
               num(t.pixel) + "\" stroke=\"" + (major ? "#dddddd" : "#f0f0f0") + "\" stroke-width=\"1\"/>\n";
        svg += "<line x1=\"" + num(left - (major ? 6 : 3)) + "\" y1=\"" + num(t.pixel) + "\" x2=\"" + num(left) +
               "\" y2=\"" + num(t.pixel) + "\" stroke=\"#333333\"/>\n";
        if (major) {
            svg += "<text x=\"" + num(left - 9) + "\" y=\"" + num(t.pixel + 4) +
                   "\" text-anchor=\"end\" font-size=\"12\">" + escape(t.label) + "</text>\n";
        }
    }
}

// One series: its line (clipped to the plot, thinned per pixel column), its markers, its isolated points.
void renderSeries(std::string& svg, const Series& s, std::size_t si, int index, const Scale& sx, const Scale& sy,
                  const PlotBox& b) {
    const double left = b.left, right = b.right, plotTop = b.top, plotBottom = b.bottom;
    const double margin = 2.0; // clip a little outside the frame; the clipPath trims the stroke exactly
    const int colourIndex = s.colour >= 0 ? s.colour : static_cast<int>(si);
    const char* colour = paletteColour(colourIndex);
    const std::size_t n = std::min(s.x.size(), s.y.size());

    std::vector<std::vector<Point>> runs;
    std::vector<Point> markers;
    bool havePrev = false;
    Point prev{0, 0};
    for (std::size_t i = 0; i < n; ++i) {
        const Point p = sx.drawable(s.x[i]) && sy.drawable(s.y[i]) ? Point{sx.toPixel(s.x[i]), sy.toPixel(s.y[i])}
                                                                   : Point{NAN, NAN};
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) { // a gap (counted above, or beyond 1e308 px)
            havePrev = false;
            continue;
        }
        if (p.x >= left - 0.5 && p.x <= right + 0.5 && p.y >= plotTop - 0.5 && p.y <= plotBottom + 0.5) {
            markers.push_back(p);
        }
        if (havePrev) {
            Point a = prev, b = p;
            if (clipSegment(a, b, left - margin, plotTop - margin, right + margin, plotBottom + margin)) {
                const bool continues =
                    !runs.empty() && !runs.back().empty() && runs.back().back().x == a.x && runs.back().back().y == a.y;
                if (!continues) runs.push_back({a});
                runs.back().push_back(b);
            }
        } else if (i + 1 >= n || !sx.drawable(s.x[i + 1]) || !sy.drawable(s.y[i + 1])) {
            // An isolated point: no line to draw, so it shows as a dot even without markers.
            if (!s.markers && p.x >= left && p.x <= right && p.y >= plotTop && p.y <= plotBottom) {
                svg += "<circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"2\" fill=\"" + colour + "\"/>\n";
            }
        }
        prev = p;
        havePrev = true;
    }
    std::string d;
    for (const auto& run : runs) {
        const auto pts = thin(run);
        for (std::size_t k = 0; k < pts.size(); ++k) {
            d += k == 0 ? 'M' : 'L';
            d += num(pts[k].x);
            d += ' ';
            d += num(pts[k].y);
        }
    }
    if (!d.empty()) {
        svg += "<path clip-path=\"url(#clip" + std::to_string(index) + ")\" fill=\"none\" stroke=\"" + colour +
               "\" stroke-width=\"" + (s.dashed ? "1.4" : "1.8") + "\" stroke-linejoin=\"round\"" +
               (s.dashed ? " stroke-dasharray=\"7 5\"" : "") + " d=\"" + d + "\"><title>" + escape(s.name) +
               "</title></path>\n";
    }
    if (s.markers) {
        const std::size_t every = markers.size() > kMaxMarkers ? (markers.size() + kMaxMarkers - 1) / kMaxMarkers : 1;
        for (std::size_t k = 0; k < markers.size(); k += every) {
            svg += markerShape(colourIndex, markers[k].x, markers[k].y, colour) + "\n";
        }
    }
}

// The legend, to the right of the plot from (lx, ly): the raster's colours, then the series.
void renderLegend(std::string& svg, const Panel& panel, bool raster, double lx, double ly) {
    if (raster) {
        for (std::size_t c = 0; c < panel.raster.colours.size() && c < panel.raster.names.size(); ++c) {
            if (panel.raster.names[c].empty()) continue;
            svg += "<rect x=\"" + num(lx + 6) + "\" y=\"" + num(ly - 6) + "\" width=\"16\" height=\"12\" fill=\"" +
                   escape(panel.raster.colours[c]) + "\" stroke=\"#333333\" stroke-width=\"0.5\"/>\n";
            svg += "<text x=\"" + num(lx + 36) + "\" y=\"" + num(ly + 4) + "\" font-size=\"12\">" +
                   escape(panel.raster.names[c]) + "</text>\n";
            ly += 19;
        }
    }
    for (std::size_t si = 0; si < panel.series.size(); ++si) {
        const Series& s = panel.series[si];
        if (!s.inLegend) continue;
        const int colourIndex = s.colour >= 0 ? s.colour : static_cast<int>(si);
        const char* colour = paletteColour(colourIndex);
        svg += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 28) + "\" y2=\"" + num(ly) +
               "\" stroke=\"" + colour + "\" stroke-width=\"2\"" + (s.dashed ? " stroke-dasharray=\"7 5\"" : "") +
               "/>\n";
        if (s.markers) svg += markerShape(colourIndex, lx + 14, ly, colour) + "\n";
        svg += "<text x=\"" + num(lx + 36) + "\" y=\"" + num(ly + 4) + "\" font-size=\"12\">" + escape(s.name) +
               "</text>\n";
        ly += 19;
    }
}

// The panel's note, with what could not be drawn (a raster that does not fit, points left as gaps) added.
std::string panelNote(const Panel& panel, bool raster, std::size_t undrawable) {
    std::string note = panel.note;
    if (!panel.raster.empty() && !raster) {
        if (!note.empty()) note += note.back() == '.' ? " " : "; ";
        note += "raster not drawn: " + std::to_string(panel.raster.cells.size()) + " cells for " +
                std::to_string(panel.raster.xEdges.size()) + " x " + std::to_string(panel.raster.yEdges.size()) +
                " edges";
    }
    if (undrawable > 0) {
        if (!note.empty()) note += note.back() == '.' ? " " : "; ";
        note += std::to_string(undrawable) + " point" + (undrawable == 1 ? "" : "s") +
                " not drawable (NaN, infinite or <= 0 on a log axis) left as gaps";
    }
    return note;
}

void renderPanel(std::string& svg, const Panel& panel, int index, int top, int width, int height) {
    const double left = kPlotLeft;
    const double right = width - kLegendWidth - 16;

    // Points that cannot be drawn are counted first, so the note (and the room it takes) is known up front.
    std::size_t undrawable = 0;
    for (const Series& s : panel.series) {
        const std::size_t n = std::min(s.x.size(), s.y.size());
        for (std::size_t i = 0; i < n; ++i) {
            undrawable += !drawableOn(panel.x.scale, s.x[i]) || !drawableOn(panel.y.scale, s.y[i]);
        }
    }
    const bool raster = rasterFits(panel.raster);
    const std::string note = panelNote(panel, raster, undrawable);
    const auto noteLines = wrap(note, static_cast<std::size_t>(std::max(20.0, (right - left) / 6.2)));
    const double noteHeight = 14.0 * static_cast<double>(noteLines.size() > 1 ? noteLines.size() - 1 : 0);

    const double plotTop = top + kPlotTopInPanel + noteHeight;
    const double plotBottom = top + height - kPlotBottomMargin;

    std::vector<double> xs, ys;
    for (const Series& s : panel.series) {
        const std::size_t n = std::min(s.x.size(), s.y.size());
        xs.insert(xs.end(), s.x.begin(), s.x.begin() + static_cast<std::ptrdiff_t>(n));
        ys.insert(ys.end(), s.y.begin(), s.y.begin() + static_cast<std::ptrdiff_t>(n));
    }
    // The y range comes only from points whose x is on the chart, so a fixed x window zooms y as well. A
    // raster's edges count whole: the axes fit around the grid it was made for.
    std::vector<double> xFit = xs;
    if (raster) xFit.insert(xFit.end(), panel.raster.xEdges.begin(), panel.raster.xEdges.end());
    Scale sx = settle(panel.x, xFit, left, right);
    std::vector<double> ysInView;
    for (std::size_t i = 0; i < xs.size(); ++i) {
        if (!sx.drawable(xs[i])) continue;
        const double px = sx.toPixel(xs[i]);
        if (px >= left - 1e-6 && px <= right + 1e-6) ysInView.push_back(ys[i]);
    }
    if (raster) ysInView.insert(ysInView.end(), panel.raster.yEdges.begin(), panel.raster.yEdges.end());
    Scale sy = settle(panel.y, ysInView, plotBottom, plotTop);

    const PlotBox box{left, right, plotTop, plotBottom};
    svg += "<g id=\"panel" + std::to_string(index) + "\">\n";
    svg += "<clipPath id=\"clip" + std::to_string(index) + "\"><rect x=\"" + num(left) + "\" y=\"" + num(plotTop) +
           "\" width=\"" + num(right - left) + "\" height=\"" + num(plotBottom - plotTop) + "\"/></clipPath>\n";
    svg += "<text x=\"" + num((left + right) / 2) + "\" y=\"" + num(top + 22) +
           "\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">" + escape(panel.title) + "</text>\n";

    renderGrid(svg, sx, sy, box);
    // The raster over the grid lines (a map crossed by them is hard to read; the ticks remain), under the frame
    // and the series.
    if (raster) renderRaster(svg, panel.raster, index, sx, sy, left, right, plotTop, plotBottom);
    svg += "<rect x=\"" + num(left) + "\" y=\"" + num(plotTop) + "\" width=\"" + num(right - left) + "\" height=\"" +
           num(plotBottom - plotTop) + "\" fill=\"none\" stroke=\"#333333\"/>\n";
    svg += "<text x=\"" + num((left + right) / 2) + "\" y=\"" + num(plotBottom + 42) +
           "\" text-anchor=\"middle\" font-size=\"13\">" + escape(panel.x.label) + "</text>\n";
    const double yMid = (plotTop + plotBottom) / 2;
    svg += "<text x=\"22\" y=\"" + num(yMid) + "\" text-anchor=\"middle\" font-size=\"13\" transform=\"rotate(-90 22 " +
           num(yMid) + ")\">" + escape(panel.y.label) + "</text>\n";

    for (std::size_t si = 0; si < panel.series.size(); ++si)
        renderSeries(svg, panel.series[si], si, index, sx, sy, box);

    renderLegend(svg, panel, raster, right + 18, plotTop + 8);

    for (std::size_t i = 0; i < noteLines.size(); ++i) {
        svg += "<text x=\"" + num((left + right) / 2) + "\" y=\"" + num(top + 40 + 14.0 * static_cast<double>(i)) +
               "\" text-anchor=\"middle\" font-size=\"11\" fill=\"#555555\">" + escape(noteLines[i]) + "</text>\n";
    }
    svg += "</g>\n";
}

} // namespace

const char* paletteColour(int index) {
    const int i = ((index % kPaletteSize) + kPaletteSize) % kPaletteSize;
    return kPalette[i];
}

std::string renderSvg(const Chart& chart) {
    if (chart.panels.empty()) throw std::invalid_argument("renderSvg: a chart needs at least one panel");
    const int width = std::max(chart.width, kPlotLeft + kLegendWidth + 120);
    const int panelHeight = std::max(chart.panelHeight, kPlotTopInPanel + kPlotBottomMargin + 60);
    const int titleHeight = chart.title.empty() ? 0 : kTitleHeight;
    const int height = titleHeight + panelHeight * static_cast<int>(chart.panels.size());

    std::string svg;
    svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + std::to_string(width) +
           "\" height=\"" + std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " +
           std::to_string(height) + "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
    svg += "<title>" + escape(chart.title) + "</title>\n";
    svg += "<rect x=\"0\" y=\"0\" width=\"" + std::to_string(width) + "\" height=\"" + std::to_string(height) +
           "\" fill=\"white\"/>\n";
    if (!chart.title.empty()) {
        svg += "<text x=\"" + std::to_string(width / 2) +
               "\" y=\"27\" text-anchor=\"middle\" font-size=\"18\" font-weight=\"bold\">" + escape(chart.title) +
               "</text>\n";
    }
    for (std::size_t i = 0; i < chart.panels.size(); ++i) {
        renderPanel(svg, chart.panels[i], static_cast<int>(i), titleHeight + panelHeight * static_cast<int>(i), width,
                    panelHeight);
    }
    svg += "</svg>\n";
    return svg;
}

std::filesystem::path writeSvg(const Chart& chart, const std::filesystem::path& path) {
    const std::string text = renderSvg(chart);
    core::AtomicFile file(path);
    file.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
    file.commit();
    return path;
}

} // namespace lab
