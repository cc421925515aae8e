// minecrappy-atlas: procedurally draws the block texture atlas (original pixel art) and writes it as a
// 256x256 RGBA PNG: 16x16 tiles of 16x16 pixels, tile i at column i % 16, row i / 16 (row 0 on top).
//
// Usage: minecrappy-atlas [--stats] OUTPUT.png
//   --stats  also prints each used tile's average RGB to stdout.
//
// Everything is integer arithmetic driven by core::hashCoords, so the output is byte-identical on every
// platform and compiler. All noise wraps at the tile edge so every tile repeats seamlessly.
#include "core/log.h"
#include "core/rng.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <vector>

namespace {

constexpr int kTile = 16; // pixels per tile side
constexpr int kGrid = 16; // tiles per atlas side
constexpr int kSize = kTile * kGrid;

struct Rgb {
    int r = 0, g = 0, b = 0;
};

constexpr int clamp255(int v) { return v < 0 ? 0 : (v > 255 ? 255 : v); }
constexpr int wrap(int v) { return ((v % kTile) + kTile) % kTile; }
// Row-major pixel index of (x, y), both in [0, kTile).
constexpr std::size_t pixelIndex(int x, int y) {
    return static_cast<std::size_t>(y) * kTile + static_cast<std::size_t>(x);
}

constexpr Rgb add(Rgb c, int d) { return {clamp255(c.r + d), clamp255(c.g + d), clamp255(c.b + d)}; }
// Linear blend a -> b by t / 256.
constexpr Rgb mix(Rgb a, Rgb b, int t) {
    return {a.r + (b.r - a.r) * t / 256, a.g + (b.g - a.g) * t / 256, a.b + (b.b - a.b) * t / 256};
}

struct Tile {
    std::array<Rgb, kTile * kTile> px{};
    Rgb& at(int x, int y) { return px[pixelIndex(wrap(x), wrap(y))]; }
    const Rgb& at(int x, int y) const { return px[pixelIndex(wrap(x), wrap(y))]; }
};

// ---- deterministic noise -------------------------------------------------------------------------

// Per-pixel hash in [0, 256), wrapped to the tile.
int h8(std::uint64_t seed, int x, int y) { return static_cast<int>(core::hashCoords(seed, wrap(x), wrap(y), 0) >> 56); }

// Smoothstep of t in [0, 256] -> [0, 256], integers only.
constexpr int smooth256(int t) { return (3 * t * t) / 256 - (2 * t * t * t) / 65536; }

// Tileable value noise in [0, 256): lattice of cellW x cellH pixel cells (both must divide 16),
// lattice values wrap at the tile edge, smoothstep-interpolated.
int valueNoise(std::uint64_t seed, int x, int y, int cellW, int cellH) {
    x = wrap(x);
    y = wrap(y);
    const int nx = kTile / cellW, ny = kTile / cellH;
    const int cx = x / cellW, cy = y / cellH;
    const int tx = smooth256((x % cellW) * 256 / cellW);
    const int ty = smooth256((y % cellH) * 256 / cellH);
    auto lat = [&](int i, int j) { return static_cast<int>(core::hashCoords(seed, i % nx, j % ny, 1) >> 56); };
    const int v00 = lat(cx, cy), v10 = lat(cx + 1, cy), v01 = lat(cx, cy + 1), v11 = lat(cx + 1, cy + 1);
    const int a = v00 * (256 - tx) + v10 * tx;
    const int b = v01 * (256 - tx) + v11 * tx;
    return (a * (256 - ty) + b * ty) / 65536;
}

// Picks a palette entry from v in [0, 256): posterised, as pixel art should be.
template <std::size_t N>
Rgb pick(const std::array<Rgb, N>& pal, int v) {
    const int i = clamp255(v) * static_cast<int>(N) / 256;
    return pal[static_cast<std::size_t>(i)];
}

// Integer square root (floor).
int isqrt(int v) {
    int r = 0;
    while ((r + 1) * (r + 1) <= v) ++r;
    return r;
}

// Squared wrapped distance between two points on the 16x16 torus, in pixels.
int torusDist2(int ax, int ay, int bx, int by) {
    int dx = wrap(ax - bx), dy = wrap(ay - by);
    if (dx > kTile / 2) dx = kTile - dx;
    if (dy > kTile / 2) dy = kTile - dy;
    return dx * dx + dy * dy;
}

struct Cells {
    std::array<int, kTile * kTile> id{};
    int at(int x, int y) const { return id[pixelIndex(wrap(x), wrap(y))]; }
};

// Wrapped Voronoi partition: one jittered seed point per (16/cell)^2 grid cell.
Cells voronoi(std::uint64_t seed, int cell, int jitter) {
    const int n = kTile / cell;
    std::vector<std::array<int, 2>> pts;
    core::Rng rng(seed);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int ox = static_cast<int>(rng.below(static_cast<std::uint32_t>(2 * jitter + 1))) - jitter;
            const int oy = static_cast<int>(rng.below(static_cast<std::uint32_t>(2 * jitter + 1))) - jitter;
            pts.push_back({i * cell + cell / 2 + ox, j * cell + cell / 2 + oy});
        }
    Cells c;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            int best = 0, bestD = 1 << 30;
            for (std::size_t k = 0; k < pts.size(); ++k) {
                const int d = torusDist2(x, y, pts[k][0], pts[k][1]);
                if (d < bestD) {
                    bestD = d;
                    best = static_cast<int>(k);
                }
            }
            c.id[pixelIndex(x, y)] = best;
        }
    return c;
}

// ---- palettes ------------------------------------------------------------------------------------

constexpr std::array<Rgb, 5> kGrass{{{58, 104, 34}, {74, 124, 40}, {90, 142, 48}, {106, 160, 56}, {124, 176, 66}}};
constexpr std::array<Rgb, 4> kDirt{{{100, 70, 46}, {118, 84, 56}, {134, 96, 65}, {148, 108, 74}}};
constexpr Rgb kDirtSpeck{78, 54, 36};
constexpr std::array<Rgb, 3> kPebble{{{112, 104, 96}, {138, 128, 116}, {156, 146, 132}}};
constexpr std::array<Rgb, 4> kSnow{{{226, 234, 242}, {236, 242, 248}, {244, 248, 252}, {250, 252, 255}}};

// ---- tiles ---------------------------------------------------------------------------------------

Tile grassTop() {
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int v = valueNoise(101, x, y, 8, 8) * 2 / 5 + valueNoise(102, x, y, 4, 4) / 5 + h8(103, x, y) * 2 / 5;
            t.at(x, y) = pick(kGrass, (v - 40) * 256 / 176);
            // Occasional blade tips: a bright pixel with a darker one below it.
            if (h8(104, x, y) < 10) {
                t.at(x, y) = kGrass[4];
                t.at(x, y + 1) = kGrass[0];
            }
        }
    return t;
}

Tile dirt(std::uint64_t seed) {
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int v = valueNoise(seed, x, y, 4, 4) / 2 + h8(seed + 1, x, y) / 2;
            t.at(x, y) = pick(kDirt, (v - 30) * 256 / 196);
            if (h8(seed + 2, x, y) < 22) t.at(x, y) = kDirtSpeck;
        }
    // A few small pebbles: 2x1 / 1x2 / 2x2 clusters with a highlight on the top-left pixel.
    core::Rng rng(seed + 3);
    for (int k = 0; k < 4; ++k) {
        const int px = static_cast<int>(rng.below(16)), py = static_cast<int>(rng.below(16));
        const int shape = static_cast<int>(rng.below(3));
        const Rgb base = kPebble[rng.below(2)];
        t.at(px, py) = kPebble[2];
        if (shape != 1) t.at(px + 1, py) = base;
        if (shape != 0) t.at(px, py + 1) = base;
        if (shape == 2) t.at(px + 1, py + 1) = kPebble[0];
    }
    return t;
}

// Dirt with a ragged fringe of `top` on the upper rows; the row below the fringe gets a shadow.
template <std::size_t N>
Tile sideFringe(std::uint64_t seed, const std::array<Rgb, N>& top, int topBias) {
    Tile t = dirt(202);
    for (int x = 0; x < kTile; ++x) {
        // Depth 3 or 4 with occasional drips to 5 and notches to 2.
        const int r = h8(seed, x, 0);
        const int depth = r < 20 ? 2 : (r < 130 ? 3 : (r < 230 ? 4 : 5));
        for (int y = 0; y < depth; ++y) {
            const int v = h8(seed + 1, x, y) / 2 + valueNoise(seed + 2, x, y, 4, 4) / 2 + topBias - y * 18;
            t.at(x, y) = pick(top, v);
        }
        if (h8(seed + 3, x, depth) < 150) t.at(x, depth) = mix(t.at(x, depth), kDirtSpeck, 160);
    }
    return t;
}

Tile stone() {
    constexpr std::array<Rgb, 5> pal{
        {{114, 114, 116}, {126, 126, 128}, {136, 136, 138}, {146, 146, 148}, {156, 156, 158}}};
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int v = valueNoise(301, x, y, 8, 8) * 2 / 5 + valueNoise(302, x, y, 4, 4) * 2 / 5 + h8(303, x, y) / 5;
            t.at(x, y) = pick(pal, (v - 50) * 256 / 150);
        }
    // Cracks: short wandering diagonal lines, dark with a faint light lip below.
    core::Rng rng(304);
    for (int k = 0; k < 3; ++k) {
        // Spread the cracks out: one per third of the tile, at different heights.
        int x = k * 5 + static_cast<int>(rng.below(3)), y = k * 6 + static_cast<int>(rng.below(4));
        const int dx = rng.below(2) ? 1 : -1;
        const int len = 3 + static_cast<int>(rng.below(3));
        for (int s = 0; s < len; ++s) {
            t.at(x, y) = {96, 96, 98};
            if (t.at(x, y + 1).r > 100) t.at(x, y + 1) = add(t.at(x, y + 1), 10);
            const std::uint32_t step = rng.below(4);
            if (step == 0)
                ++y;
            else if (step == 1)
                x += dx;
            else {
                x += dx;
                ++y;
            }
        }
    }
    return t;
}

Tile sand() {
    constexpr std::array<Rgb, 4> pal{{{206, 190, 138}, {216, 202, 150}, {224, 211, 160}, {232, 220, 172}}};
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int v = valueNoise(401, x, y, 8, 8) / 4 + h8(402, x, y) * 3 / 4;
            t.at(x, y) = pick(pal, (v - 20) * 256 / 216);
            if (h8(403, x, y) < 6) t.at(x, y) = {190, 170, 120};
        }
    return t;
}

constexpr std::array<Rgb, 5> kBark{{{60, 45, 27}, {78, 59, 35}, {96, 73, 44}, {110, 85, 52}, {124, 97, 60}}};

Tile logSide() {
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            // Stretched vertically: narrow columns, long runs.
            const int v = valueNoise(501, x, y, 2, 8) * 3 / 5 + valueNoise(502, x, y, 1, 16) / 5 + h8(503, x, y) / 5;
            t.at(x, y) = pick(kBark, (v - 40) * 256 / 176);
        }
    // Deep furrows: dark vertical streaks.
    core::Rng rng(504);
    for (int k = 0; k < 5; ++k) {
        const int x = static_cast<int>(rng.below(16)), y = static_cast<int>(rng.below(16));
        const int len = 4 + static_cast<int>(rng.below(6));
        for (int s = 0; s < len; ++s) t.at(x, y + s) = kBark[0];
        t.at(x + 1, y + len / 2) = kBark[4];
    }
    return t;
}

Tile logTop() {
    constexpr std::array<Rgb, 2> wood{{{188, 152, 98}, {164, 128, 78}}};
    constexpr Rgb ring{138, 104, 60};
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int edge = std::min(std::min(x, y), std::min(kTile - 1 - x, kTile - 1 - y));
            if (edge == 0) {
                t.at(x, y) = pick(kBark, h8(601, x, y) * 3 / 4);
                continue;
            }
            // Distance from the centre (7.5, 7.5) in half pixels, slightly wobbled.
            const int dx = 2 * x + 1 - kTile, dy = 2 * y + 1 - kTile;
            const int rh = isqrt(dx * dx + dy * dy) + (h8(602, x, y) < 40 ? 1 : 0);
            Rgb c = wood[static_cast<std::size_t>((rh / 3) % 2)];
            if (rh % 6 == 5) c = ring;
            if (edge == 1) c = mix(c, kBark[1], 96); // inner bark shadow
            t.at(x, y) = add(c, (h8(603, x, y) - 128) / 24);
        }
    return t;
}

Tile leaves() {
    constexpr std::array<Rgb, 5> pal{{{34, 74, 24}, {46, 92, 30}, {56, 108, 36}, {66, 122, 42}, {80, 138, 50}}};
    constexpr Rgb hole{22, 48, 16};
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int v = valueNoise(701, x, y, 4, 4) * 2 / 5 + h8(702, x, y) * 3 / 5;
            t.at(x, y) = pick(pal, (v - 30) * 256 / 196);
        }
    // Holes: dark pixels, each with a lit leaf edge above it.
    core::Rng rng(703);
    for (int k = 0; k < 18; ++k) {
        const int x = static_cast<int>(rng.below(16)), y = static_cast<int>(rng.below(16));
        t.at(x, y) = hole;
        if (rng.below(2)) t.at(x + 1, y) = hole;
        t.at(x, y - 1) = pal[4];
    }
    return t;
}

Tile planks() {
    constexpr std::array<Rgb, 4> pal{{{180, 138, 84}, {194, 150, 92}, {206, 162, 100}, {216, 172, 108}}};
    constexpr Rgb seam{112, 80, 46};
    Tile t;
    for (int board = 0; board < 4; ++board) {
        // Each board has one butt joint; staggered between boards.
        constexpr std::array<int, 4> joint{{3, 11, 7, 15}};
        const int tone = (board % 2 == 0) ? 0 : -6;
        for (int row = 0; row < 4; ++row) {
            const int y = board * 4 + row;
            for (int x = 0; x < kTile; ++x) {
                if (row == 3) {
                    t.at(x, y) = seam;
                    continue;
                }
                // Grain: stretched horizontally.
                const int v =
                    valueNoise(801 + static_cast<std::uint64_t>(board), x, y, 8, 1) * 3 / 5 + h8(805, x, y) * 2 / 5;
                Rgb c = add(pick(pal, (v - 30) * 256 / 196), tone);
                if (row == 0) c = add(c, 8);  // lit top edge
                if (row == 2) c = add(c, -8); // shaded bottom edge
                t.at(x, y) = c;
            }
            const int jx = joint[static_cast<std::size_t>(board)];
            if (row != 3) t.at(jx, y) = mix(seam, pal[0], 64);
        }
        // A few nail dots near the board ends.
        if (board != 1) {
            const int jx = joint[static_cast<std::size_t>(board)];
            t.at(jx + (board == 2 ? -2 : 2), board * 4 + 1) = {78, 66, 56};
        }
    }
    return t;
}

Tile brick() {
    constexpr std::array<Rgb, 4> pal{{{142, 40, 28}, {160, 48, 34}, {176, 56, 40}, {190, 66, 46}}};
    constexpr Rgb mortar{170, 166, 160};
    Tile t;
    for (int y = 0; y < kTile; ++y) {
        const int course = y / 4, row = y % 4;
        const int shift = (course % 2) * 4;
        for (int x = 0; x < kTile; ++x) {
            const int bx = wrap(x + shift);
            if (row == 3 || bx % 8 == 7) {
                t.at(x, y) = add(mortar, (h8(901, x, y) - 128) / 20);
                continue;
            }
            const int brickId = course * 2 + bx / 8;
            const int tone = (h8(902, brickId, 0) - 128) / 5; // per-brick variation
            const int v = h8(903, x, y) * 3 / 4 + valueNoise(904, x, y, 4, 4) / 4 + tone;
            Rgb c = pick(pal, v);
            if (row == 0) c = add(c, 10);     // top edge catches light
            if (bx % 8 == 6) c = add(c, -10); // right edge in shade
            t.at(x, y) = c;
        }
    }
    return t;
}

Tile cobblestone() {
    constexpr std::array<Rgb, 4> pal{{{96, 96, 98}, {112, 112, 114}, {126, 126, 128}, {140, 140, 142}}};
    constexpr Rgb gap{52, 52, 54};
    const Cells cells = voronoi(1001, 4, 1);
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int id = cells.at(x, y);
            const bool isGap = cells.at(x + 1, y) != id || cells.at(x, y + 1) != id;
            if (isGap) {
                t.at(x, y) = gap;
                continue;
            }
            const int tone = (h8(1002, id, 0) - 128) / 3;
            const int v = 128 + tone + (h8(1003, x, y) - 128) / 2;
            Rgb c = pick(pal, v);
            // Top-left light: lighter where the stone meets a gap above/left, darker below/right.
            if (cells.at(x, y - 1) != id || cells.at(x - 1, y) != id)
                c = add(c, 16);
            else if (cells.at(x + 1, y + 1) != id || cells.at(x, y + 2) != id)
                c = add(c, -14);
            t.at(x, y) = c;
        }
    return t;
}

Tile snow() {
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const int v = valueNoise(1101, x, y, 8, 8) / 2 + h8(1102, x, y) / 2;
            t.at(x, y) = pick(kSnow, (v - 30) * 256 / 196);
            if (h8(1103, x, y) < 14) t.at(x, y) = {206, 216, 230};
        }
    return t;
}

Tile gravel() {
    constexpr std::array<Rgb, 6> stones{
        {{138, 134, 132}, {118, 114, 112}, {158, 154, 150}, {140, 124, 108}, {122, 108, 96}, {150, 138, 124}}};
    constexpr Rgb gap{90, 84, 80};
    const Cells cells = voronoi(1301, 4, 1);
    const Cells fine = voronoi(1302, 2, 1);
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            // Split some coarse cells with a finer partition so pebbles vary in size.
            const auto id = [&](int px, int py) {
                const int c = cells.at(px, py);
                return h8(1303, c, 0) < 110 ? c * 64 + fine.at(px, py) : c * 64;
            };
            const int me = id(x, y);
            if (id(x + 1, y) != me || id(x, y + 1) != me) {
                t.at(x, y) = h8(1304, x, y) < 170 ? gap : stones[4];
                continue;
            }
            const int s = h8(1305, me, 1) % static_cast<int>(stones.size());
            Rgb c = add(stones[static_cast<std::size_t>(s)], (h8(1306, x, y) - 128) / 16);
            if (id(x, y - 1) != me || id(x - 1, y) != me) c = add(c, 16);
            t.at(x, y) = c;
        }
    return t;
}

// A lamp: a glowing pane of colour `glow` (its brightest, the middle of each pane) behind a dark iron frame and
// cross bars; `seed` varies the grain.
Tile lamp(Rgb glowAt, std::uint32_t seed) {
    constexpr Rgb frame{58, 52, 48}, frameLight{92, 84, 76};
    Tile t;
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) {
            const bool edge = x == 0 || y == 0 || x == kTile - 1 || y == kTile - 1;
            const bool bar = x == 7 || x == 8 || y == 7 || y == 8;
            if (edge || bar) {
                t.at(x, y) = (x + y) % 5 == 0 ? frameLight : frame;
                continue;
            }
            // Brightest in the middle of each pane, a little grain.
            const int cx = x < 8 ? 4 : 11, cy = y < 8 ? 4 : 11;
            const int d = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            const int glow = 255 - d * 6 + (h8(seed, x, y) - 128) / 12;
            t.at(x, y) = {clamp255(glow * glowAt.r / 255), clamp255(glow * glowAt.g / 255),
                          clamp255(glow * glowAt.b / 255)};
        }
    return t;
}

struct Entry {
    int index;
    const char* name;
    Tile tile;
};

std::vector<Entry> buildTiles() {
    return {
        {0, "grass_top", grassTop()},
        {1, "grass_side", sideFringe(1201, kGrass, 40)},
        {2, "dirt", dirt(202)},
        {3, "stone", stone()},
        {4, "sand", sand()},
        {5, "log_side", logSide()},
        {6, "log_top", logTop()},
        {7, "leaves", leaves()},
        {8, "planks", planks()},
        {9, "brick", brick()},
        {10, "cobblestone", cobblestone()},
        {11, "snow", snow()},
        {12, "snow_side", sideFringe(1211, kSnow, 90)},
        {13, "gravel", gravel()},
        {14, "lamp", lamp({255, 215, 120}, 1401)},
        {15, "red_lamp", lamp({255, 60, 40}, 1501)},
        {16, "green_lamp", lamp({70, 255, 80}, 1601)},
        {17, "blue_lamp", lamp({70, 120, 255}, 1701)},
        {18, "warm_lamp", lamp({255, 175, 90}, 1801)},
        {19, "orange_lamp", lamp({255, 130, 20}, 1901)},
    };
}

int usage(const char* argv0) {
    std::fprintf(stderr, "usage: %s [--stats] OUTPUT.png\n", argv0);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    core::setLogProgram("minecrappy-atlas");
    const char* argv0 = argc > 0 ? argv[0] : "minecrappy-atlas";
    bool stats = false;
    const char* out = nullptr;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if (a == "--stats" && !stats)
            stats = true;
        else if (!out && !(a.size() > 1 && a[0] == '-'))
            out = argv[i];
        else
            return usage(argv0);
    }
    if (!out) return usage(argv0);

    std::vector<unsigned char> img(static_cast<std::size_t>(kSize) * kSize * 4, 0);
    for (const Entry& e : buildTiles()) {
        const int ox = (e.index % kGrid) * kTile, oy = (e.index / kGrid) * kTile;
        long sr = 0, sg = 0, sb = 0;
        for (int y = 0; y < kTile; ++y)
            for (int x = 0; x < kTile; ++x) {
                const Rgb& c = e.tile.at(x, y);
                unsigned char* p =
                    &img[(static_cast<std::size_t>(oy + y) * kSize + static_cast<std::size_t>(ox + x)) * 4];
                p[0] = static_cast<unsigned char>(clamp255(c.r));
                p[1] = static_cast<unsigned char>(clamp255(c.g));
                p[2] = static_cast<unsigned char>(clamp255(c.b));
                p[3] = 255;
                sr += p[0];
                sg += p[1];
                sb += p[2];
            }
        if (stats) {
            constexpr long n = kTile * kTile;
            std::printf("%2d %-12s %3ld %3ld %3ld\n", e.index, e.name, (sr + n / 2) / n, (sg + n / 2) / n,
                        (sb + n / 2) / n);
        }
    }

    if (!stbi_write_png(out, kSize, kSize, 4, img.data(), kSize * 4)) {
        core::logError("failed to write '%s'", out);
        return 1;
    }
    return 0;
}
