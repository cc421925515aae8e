// A small SVG line-chart writer for the lab's studies: one or more panels stacked vertically, each with
// a title, labelled linear or log10 axes, several named series (colour-blind-friendly Okabe-Ito palette,
// a distinct marker shape per series), dashed reference lines and a legend.
// Points that cannot be drawn (NaN, infinity, or <= 0 on a log axis) leave a gap in the line; they are
// counted and mentioned on the panel, never drawn at a made-up place. Dense series are thinned per pixel
// column (first, lowest, highest and last point kept), so a 60 000-point run looks the same and stays small.
// It must never depend on anything beyond the standard library, and never write a half-finished file.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lab {

enum class AxisScale { Linear, Log10 };

struct Axis {
    std::string label; // shown beside the axis, units included: "dt (s)"
    AxisScale scale = AxisScale::Linear;
    std::optional<double> min; // fixed range; unset: fitted to the data (log: whole decades)
    std::optional<double> max; // points outside a fixed range are clipped at the plot edge
};

struct Series {
    std::string name;      // legend text
    std::vector<double> x; // same length as y; extra points of the longer one are ignored
    std::vector<double> y;
    int colour = -1;      // palette index (kPaletteSize wraps); -1: the series' position
    bool markers = false; // draw a marker (shape by colour index) at every point
    bool dashed = false;  // a reference line: dashed, thinner
    bool inLegend = true;
};

struct Panel {
    std::string title;
    Axis x;
    Axis y;
    std::vector<Series> series;
    std::string note; // one line of small text under the title; may be empty
};

struct Chart {
    std::string title;
    std::vector<Panel> panels;
    int width = 960;       // pixels
    int panelHeight = 380; // pixels per panel, title and axis labels included
};

inline constexpr int kPaletteSize = 8;
// Okabe & Ito's palette, reordered so the first colours are the most distinct on white.
const char* paletteColour(int index);

// The whole document. Never throws for odd data; throws std::invalid_argument for a chart with no panels.
std::string renderSvg(const Chart& chart);

// Writes renderSvg(chart) to `path` through a temporary file in the same folder and a rename, so an
// existing file is either replaced whole or left as it was. Throws std::runtime_error naming the path.
void writeSvg(const Chart& chart, const std::filesystem::path& path);

} // namespace lab
