// A small SVG line-chart writer for the lab's studies: one or more panels stacked vertically, each with
// a title, labelled linear or log10 axes, several named series (colour-blind-friendly Okabe-Ito palette,
// a distinct marker shape per series), dashed reference lines and a legend, and optionally a raster of
// coloured cells under the series (a map of which cells of a grid have some property).
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

// Cells of a grid on the panel's axes, drawn over the grid lines and under the series, through the same axis
// mapping (a log axis gives cells of equal height per decade). Each row's runs of equal neighbouring cells
// become one <rect>, so a 90 x 80 map of two colours takes about a hundred rects (measured: 808 for the seven
// stability maps), not 7200. A cell whose colour is -1 (or not in
// `colours`) is not drawn, nor is one with an edge the axis cannot show (<= 0 on a log axis, NaN); cells are
// clipped to the plot area. A raster whose cells do not match its edges is not drawn at all (the note says so).
struct Raster {
    std::vector<double> xEdges;       // nx + 1 increasing cell edges along x (data units)
    std::vector<double> yEdges;       // ny + 1 increasing cell edges along y
    std::vector<int> cells;           // ny * nx colour indices, row-major: cells[row * nx + column]; row 0 is
                                      // the one between yEdges[0] and yEdges[1]
    std::vector<std::string> colours; // fill per colour index: "#rrggbb"
    std::vector<std::string> names;   // legend text per colour index (a swatch each); missing or empty: none

    bool empty() const { return cells.empty(); }
};

struct Panel {
    std::string title;
    Axis x;
    Axis y;
    std::vector<Series> series;
    std::string note;   // one line of small text under the title; may be empty
    Raster raster = {}; // optional (empty: none); its edges count when fitting the axes
};

struct Chart {
    std::string title;
    std::vector<Panel> panels;
    int width = 960;       // pixels
    int panelHeight = 380; // pixels per panel, title and axis labels included
};

inline constexpr int kPaletteSize = 10;
// Okabe & Ito's palette, reordered so the first colours are the most distinct on white, then two of Paul Tol's.
const char* paletteColour(int index);

// The whole document. Never throws for odd data; throws std::invalid_argument for a chart with no panels.
std::string renderSvg(const Chart& chart);

// Writes renderSvg(chart) to `path` through a temporary file in the same folder and a rename, so an
// existing file is either replaced whole or left as it was; returns `path` (as writeCsvFile does, for the
// list of files written). Throws std::runtime_error naming the path.
std::filesystem::path writeSvg(const Chart& chart, const std::filesystem::path& path);

} // namespace lab
