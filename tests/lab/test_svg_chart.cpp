// SVG chart writer: the document is well-formed XML, odd data leaves gaps instead of breaking it, log axes
// cope with values they cannot show, and files are written whole or not at all.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../temp_dir.h"
#include "lab/svg_chart.h"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A small well-formedness check: every tag closes in order, attributes are quoted, no stray '<' or '&'.
// Returns an empty string when the document is fine, else what is wrong.
std::string xmlProblem(const std::string& doc) {
    std::vector<std::string> open;
    std::size_t i = 0;
    bool sawRoot = false;
    while (i < doc.size()) {
        if (doc[i] == '&') {
            const auto semi = doc.find(';', i);
            const std::string ent = semi == std::string::npos ? "" : doc.substr(i, semi - i + 1);
            if (ent != "&amp;" && ent != "&lt;" && ent != "&gt;" && ent != "&quot;" && ent != "&apos;") {
                return "bad entity at " + std::to_string(i);
            }
            i = semi + 1;
            continue;
        }
        if (doc[i] != '<') {
            ++i;
            continue;
        }
        const auto close = doc.find('>', i);
        if (close == std::string::npos) return "unclosed '<' at " + std::to_string(i);
        const std::string tag = doc.substr(i + 1, close - i - 1);
        i = close + 1;
        if (tag.empty()) return "empty tag";
        if (tag[0] == '?') continue; // XML declaration
        if (tag[0] == '/') {
            if (open.empty() || open.back() != tag.substr(1)) return "mismatched </" + tag.substr(1) + ">";
            open.pop_back();
            continue;
        }
        if (tag.find('<') != std::string::npos) return "'<' inside a tag";
        const bool selfClosing = tag.back() == '/';
        const std::string name = tag.substr(0, tag.find_first_of(" \n/"));
        // Attribute values must be quoted: count quotes.
        std::size_t quotes = 0;
        for (char c : tag) quotes += c == '"';
        if (quotes % 2 != 0) return "unbalanced quotes in <" + name + ">";
        if (open.empty() && sawRoot) return "content after the root element";
        if (open.empty()) {
            if (name != "svg") return "root is <" + name + ">, not <svg>";
            sawRoot = true;
        }
        if (!selfClosing) open.push_back(name);
    }
    if (!open.empty()) return "unclosed <" + open.back() + ">";
    if (!sawRoot) return "no root element";
    return {};
}

std::size_t count(const std::string& haystack, const std::string& needle) {
    std::size_t n = 0;
    for (auto p = haystack.find(needle); p != std::string::npos; p = haystack.find(needle, p + 1)) ++n;
    return n;
}

// The d attribute of the path whose <title> is `name`.
std::string pathData(const std::string& svg, const std::string& name) {
    const auto title = svg.find("<title>" + name + "</title></path>");
    if (title == std::string::npos) return {};
    const auto d = svg.rfind(" d=\"", title);
    return svg.substr(d + 4, svg.find('"', d + 4) - d - 4);
}

lab::Chart twoPanels() {
    lab::Chart c;
    c.title = "Title with <angle> & \"quotes\"";
    lab::Panel a{
        "theta", {"t (s)", lab::AxisScale::Linear, {}, {}}, {"theta (rad)", lab::AxisScale::Linear, {}, {}}, {}, {}};
    lab::Series s1{"sin", {}, {}, -1, false, false, true};
    lab::Series s2{"cos & co", {}, {}, -1, true, false, true};
    for (int i = 0; i <= 50; ++i) {
        const double t = i * 0.1;
        s1.x.push_back(t);
        s1.y.push_back(std::sin(t));
        s2.x.push_back(t);
        s2.y.push_back(std::cos(t));
    }
    a.series = {s1, s2, lab::Series{"reference", {0.0, 5.0}, {0.5, 0.5}, 6, false, true, false}};
    lab::Panel b{"error", {"dt (s)", lab::AxisScale::Log10, {}, {}}, {"error", lab::AxisScale::Log10, {}, {}}, {}, {}};
    b.series = {lab::Series{"euler", {1e-3, 1e-2, 1e-1}, {1e-4, 1e-3, 1e-2}, -1, true, false, true}};
    c.panels = {a, b};
    return c;
}

std::filesystem::path freshDir(const std::string& what) { return test_util::freshRandomTempDir("mc_svg_test_", what); }

TEST(SvgChart, DocumentIsWellFormedWithOnePanelGroupEach) {
    const std::string svg = lab::renderSvg(twoPanels());
    EXPECT_EQ(xmlProblem(svg), "");
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
    EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
    EXPECT_EQ(count(svg, "<g id=\"panel"), 2u);
    EXPECT_NE(svg.find("Title with &lt;angle&gt; &amp; &quot;quotes&quot;"), std::string::npos);
    EXPECT_NE(svg.find("cos &amp; co"), std::string::npos); // legend entry, escaped
    EXPECT_NE(svg.find("t (s)"), std::string::npos);        // axis labels
    EXPECT_NE(svg.find("theta (rad)"), std::string::npos);
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos); // the dashed reference
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(SvgChart, SeriesGetDistinctColours) {
    const std::string svg = lab::renderSvg(twoPanels());
    const std::string sinPath = svg.substr(0, svg.find("<title>sin</title>"));
    const std::string cosPath = svg.substr(0, svg.find("<title>cos &amp; co</title>"));
    const auto colourOf = [](const std::string& upTo) {
        const auto p = upTo.rfind("stroke=\"#");
        return upTo.substr(p + 8, 7);
    };
    EXPECT_NE(colourOf(sinPath), colourOf(cosPath));
    EXPECT_STRNE(lab::paletteColour(0), lab::paletteColour(1));
    EXPECT_STREQ(lab::paletteColour(lab::kPaletteSize), lab::paletteColour(0)); // wraps
}

TEST(SvgChart, LogAxisShowsDecadeLabels) {
    lab::Chart c;
    c.panels = {lab::Panel{"p", {"x", lab::AxisScale::Log10, {}, {}}, {"y", lab::AxisScale::Log10, {}, {}}, {}, {}}};
    c.panels[0].series = {lab::Series{"s", {1e-5, 1e-4, 1e-3}, {2e-9, 1e-7, 5e-6}, -1, true, false, true}};
    const std::string svg = lab::renderSvg(c);
    EXPECT_EQ(xmlProblem(svg), "");
    for (const char* label : {">1e-5<", ">1e-4<", ">1e-3<", ">1e-9<", ">1e-6<"}) {
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    }
}

TEST(SvgChart, LogAxisLeavesNonPositiveValuesOutAsGaps) {
    lab::Chart c;
    c.panels = {lab::Panel{"p", {"x", lab::AxisScale::Log10, {}, {}}, {"y", lab::AxisScale::Linear, {}, {}}, {}, {}}};
    c.panels[0].series = {
        lab::Series{"s", {1.0, 10.0, -5.0, 0.0, 100.0, 1000.0}, {1, 2, 3, 4, 5, 6}, -1, false, false, true}};
    std::string svg;
    ASSERT_NO_THROW(svg = lab::renderSvg(c));
    EXPECT_EQ(xmlProblem(svg), "");
    EXPECT_NE(svg.find("2 points not drawable"), std::string::npos);
    EXPECT_EQ(count(pathData(svg, "s"), "M"), 2u); // split into two runs at the gap

    // Nothing drawable at all, and a fixed log bound <= 0: still a valid (empty) chart, not an exception.
    c.panels[0].series = {lab::Series{"all bad", {-1.0, 0.0}, {1, 2}, -1, true, false, true}};
    c.panels[0].x.min = -3.0;
    ASSERT_NO_THROW(svg = lab::renderSvg(c));
    EXPECT_EQ(xmlProblem(svg), "");
    EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(SvgChart, NaNAndInfinityBreakTheLine) {
    lab::Chart c;
    c.panels = {lab::Panel{"p", {"x", lab::AxisScale::Linear, {}, {}}, {"y", lab::AxisScale::Linear, {}, {}}, {}, {}}};
    c.panels[0].series = {
        lab::Series{"gappy", {0, 1, 2, 3, 4, 5, 6, 7}, {1, 2, kNaN, 3, 4, kInf, 5, 6}, -1, false, false, true}};
    const std::string svg = lab::renderSvg(c);
    EXPECT_EQ(xmlProblem(svg), "");
    const std::string d = pathData(svg, "gappy");
    EXPECT_EQ(count(d, "M"), 3u) << d;
    EXPECT_EQ(count(d, "L"), 3u) << d;                                         // 2 + 2 + 2 points, one line each
    EXPECT_EQ(d.find_first_not_of("ML0123456789.- "), std::string::npos) << d; // no "nan", no "inf"
    EXPECT_NE(svg.find("2 points not drawable"), std::string::npos);
}

TEST(SvgChart, FixedRangeClipsFarPointsInsteadOfDrawingThem) {
    lab::Chart c;
    c.panels = {
        lab::Panel{"p", {"x", lab::AxisScale::Linear, 0.0, 10.0}, {"y", lab::AxisScale::Linear, -1.0, 1.0}, {}, {}}};
    c.panels[0].series = {lab::Series{"wild", {0, 5, 6, 10}, {0, 1e300, -1e300, 0}, -1, false, false, true}};
    const std::string svg = lab::renderSvg(c);
    EXPECT_EQ(xmlProblem(svg), "");
    const std::string d = pathData(svg, "wild");
    ASSERT_FALSE(d.empty());
    std::string spaced;
    for (char ch : d) spaced += (ch == 'M' || ch == 'L') ? ' ' : ch;
    double biggest = 0.0;
    std::istringstream nums(spaced);
    for (double v; nums >> v;) biggest = std::max(biggest, std::fabs(v));
    EXPECT_LT(biggest, 2000.0) << d; // every coordinate stays near the canvas
}

TEST(SvgChart, DenseSeriesStayCompact) {
    lab::Chart c;
    c.panels = {lab::Panel{"p", {"t", lab::AxisScale::Linear, {}, {}}, {"y", lab::AxisScale::Linear, {}, {}}, {}, {}}};
    lab::Series s{"dense", {}, {}, -1, false, false, true};
    for (int i = 0; i < 200000; ++i) {
        s.x.push_back(i * 1e-4);
        s.y.push_back(std::sin(i * 1e-3));
    }
    c.panels[0].series = {s};
    const std::string svg = lab::renderSvg(c);
    EXPECT_EQ(xmlProblem(svg), "");
    EXPECT_LT(svg.size(), 200000u); // a few points per pixel column, not 200 000 points
}

// x, y, width, height of every <rect> in the raster group of panel `index`; empty when there is no group.
struct Rect {
    double x, y, width, height;
    std::string fill;
};
std::vector<Rect> rasterRects(const std::string& svg, int index) {
    std::vector<Rect> out;
    const auto group = svg.find("<g id=\"raster" + std::to_string(index) + "\"");
    if (group == std::string::npos) return out;
    const std::string body = svg.substr(group, svg.find("</g>", group) - group);
    auto attr = [](const std::string& tag, const std::string& name) {
        const auto at = tag.find(" " + name + "=\"");
        const auto from = at + name.size() + 3;
        return tag.substr(from, tag.find('"', from) - from);
    };
    for (auto p = body.find("<rect"); p != std::string::npos; p = body.find("<rect", p + 1)) {
        const std::string tag = body.substr(p, body.find("/>", p) - p);
        out.push_back({std::stod(attr(tag, "x")), std::stod(attr(tag, "y")), std::stod(attr(tag, "width")),
                       std::stod(attr(tag, "height")), attr(tag, "fill")});
    }
    return out;
}

lab::Chart rasterChart(const lab::Raster& raster, lab::AxisScale yScale) {
    lab::Chart c;
    c.panels = {lab::Panel{"map", {"x", lab::AxisScale::Linear, {}, {}}, {"y", yScale, {}, {}}, {}, {}, raster}};
    return c;
}

TEST(SvgChart, RasterMergesEqualNeighboursInARowAndSkipsCellsWithoutColour) {
    lab::Raster r;
    r.xEdges = {0.0, 1.0, 2.0, 3.0};
    r.yEdges = {0.0, 1.0, 2.0};
    // Row 0 (y from 0 to 1): two rects, the first two cells merged. Row 1: no colour, then one rect for two 1s.
    r.cells = {0, 0, 1, -1, 1, 1};
    r.colours = {"#112233", "#445566"};
    r.names = {"yes", ""};
    const std::string svg = lab::renderSvg(rasterChart(r, lab::AxisScale::Linear));
    EXPECT_EQ(xmlProblem(svg), "");
    const auto rects = rasterRects(svg, 0);
    ASSERT_EQ(rects.size(), 3u) << svg;
    EXPECT_EQ(rects[0].fill, "#112233");
    EXPECT_EQ(rects[1].fill, "#445566");
    EXPECT_EQ(rects[2].fill, "#445566");
    EXPECT_NEAR(rects[0].width, 2.0 * rects[1].width, 0.02); // two cells wide against one
    EXPECT_NEAR(rects[2].width, rects[0].width, 0.02);
    EXPECT_NEAR(rects[2].x, rects[1].x - rects[1].width, 0.02); // row 1 starts one cell in
    EXPECT_LT(rects[2].y, rects[0].y);                          // row 1 is above row 0 (y grows upwards)
    // The legend: a swatch and the name for colour 0; colour 1 has no name, so no entry.
    EXPECT_NE(svg.find(">yes</text>"), std::string::npos);
    EXPECT_EQ(count(svg, "fill=\"#445566\""), 2u);

    // No colour, or a colour index beyond the list: nothing drawn, not even an empty-looking rect.
    r.cells = {-1, -1, 2, -1, 7, -1};
    const auto none = rasterRects(lab::renderSvg(rasterChart(r, lab::AxisScale::Linear)), 0);
    EXPECT_TRUE(none.empty());
}

TEST(SvgChart, RasterCellsFollowALogAxis) {
    lab::Raster r;
    r.xEdges = {0.0, 1.0};
    r.yEdges = {1e-2, 1e-1, 1e2}; // one decade, then three
    r.cells = {0, 1};
    r.colours = {"#112233", "#445566"};
    const std::string svg = lab::renderSvg(rasterChart(r, lab::AxisScale::Log10));
    EXPECT_EQ(xmlProblem(svg), "");
    const auto rects = rasterRects(svg, 0);
    ASSERT_EQ(rects.size(), 2u);
    // The axis fits the edges (whole decades 1e-2 .. 1e2), so the rows fill the plot, 1 : 3 by decades.
    EXPECT_NEAR(rects[1].height, 3.0 * rects[0].height, 0.05);
    EXPECT_NEAR(rects[1].y + rects[1].height, rects[0].y, 0.02); // the 1e-1 edge is shared
    EXPECT_NE(svg.find(">0.01<"), std::string::npos);
    EXPECT_NE(svg.find(">100<"), std::string::npos);
    // The 1e-1 edge sits a quarter of the way up the plot area (the clip rectangle).
    const auto clip = svg.find("<clipPath id=\"clip0\"><rect");
    ASSERT_NE(clip, std::string::npos);
    const auto yAt = svg.find(" y=\"", clip) + 4;
    const auto hAt = svg.find(" height=\"", clip) + 9;
    const double plotTop = std::stod(svg.substr(yAt)), plotHeight = std::stod(svg.substr(hAt));
    EXPECT_NEAR(rects[0].y, plotTop + 0.75 * plotHeight, 0.02);
    EXPECT_NEAR(rects[1].y, plotTop, 0.02);

    // An edge a log axis cannot show (0) drops the row it bounds, and only that row.
    r.yEdges = {0.0, 1e-1, 1e2};
    const auto kept = rasterRects(lab::renderSvg(rasterChart(r, lab::AxisScale::Log10)), 0);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_EQ(kept[0].fill, "#445566");
}

TEST(SvgChart, RasterThatDoesNotFitItsEdgesIsLeftOutAndSaysSo) {
    lab::Raster r;
    r.xEdges = {0.0, 1.0, 2.0};
    r.yEdges = {0.0, 1.0};
    r.cells = {0, 0, 0}; // three cells for a 2 x 1 grid
    r.colours = {"#112233"};
    std::string svg;
    ASSERT_NO_THROW(svg = lab::renderSvg(rasterChart(r, lab::AxisScale::Linear)));
    EXPECT_EQ(xmlProblem(svg), "");
    EXPECT_EQ(svg.find("<g id=\"raster0\""), std::string::npos);
    EXPECT_NE(svg.find("raster not drawn"), std::string::npos);
}

TEST(SvgChart, NoPanelsIsAnError) { EXPECT_THROW(lab::renderSvg(lab::Chart{}), std::invalid_argument); }

TEST(SvgChart, WritesTheFileWholeAndNamesThePathOnFailure) {
    const auto dir = freshDir("write");
    const auto file = dir / "chart.svg";
    lab::writeSvg(twoPanels(), file);
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), lab::renderSvg(twoPanels()));

    const auto bad = dir / "no" / "such" / "folder" / "chart.svg";
    try {
        lab::writeSvg(twoPanels(), bad);
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
    }
    // Nothing but the one chart is left in the folder: no temporary files.
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
    EXPECT_EQ(entries, 1u);
    std::filesystem::remove_all(dir);
}

} // namespace
