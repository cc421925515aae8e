#include "render/occlusion_buffer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <limits>
#include <stdexcept>

namespace render {

namespace {
constexpr float kInfinity = std::numeric_limits<float>::infinity();
// How far inside an occluder's silhouette a pixel must lie, and how far a tested box's silhouette is
// widened, in buffer pixels: covers the rounding of the projection here and the rasteriser's snapping
// of vertices to its subpixel grid (a tenth of a buffer pixel is 0.8 pixels of a 1280 x 720 frame).
constexpr float kInset = 0.1f;

// v rounded down (or up) to an integer within [low, high], clamped before the conversion so that no
// value (an infinity, NaN, a point far off the screen) is out of int's range.
int floorWithin(float v, int low, int high) {
    if (!(v >= static_cast<float>(low))) return low;
    if (v >= static_cast<float>(high)) return high;
    return static_cast<int>(std::floor(v));
}
int ceilWithin(float v, int low, int high) {
    if (!(v >= static_cast<float>(low))) return low;
    if (v >= static_cast<float>(high)) return high;
    return static_cast<int>(std::ceil(v));
}

float cross(glm::vec2 o, glm::vec2 a, glm::vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// The convex hull of the points, counter-clockwise (y up), without collinear points (monotone chain).
int convexHull(std::array<glm::vec2, 8> p, std::array<glm::vec2, 16>& hull) {
    std::sort(p.begin(), p.end(), [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    int k = 0;
    for (const glm::vec2& q : p) { // lower hull
        while (k >= 2 && cross(hull[static_cast<std::size_t>(k - 2)], hull[static_cast<std::size_t>(k - 1)], q) <= 0.0f)
            --k;
        hull[static_cast<std::size_t>(k++)] = q;
    }
    const int lower = k + 1;
    for (int i = static_cast<int>(p.size()) - 2; i >= 0; --i) { // upper hull
        const glm::vec2 q = p[static_cast<std::size_t>(i)];
        while (k >= lower &&
               cross(hull[static_cast<std::size_t>(k - 2)], hull[static_cast<std::size_t>(k - 1)], q) <= 0.0f)
            --k;
        hull[static_cast<std::size_t>(k++)] = q;
    }
    return k - 1; // the last point repeats the first
}
} // namespace

OcclusionBuffer::OcclusionBuffer(int width, int height)
    : m_width(std::max(width, 1)), m_height(std::max(height, 1)),
      m_depth(static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height), kInfinity) {}

void OcclusionBuffer::clear(const glm::mat4& viewProjection) {
    m_viewProjection = viewProjection;
    std::fill(m_depth.begin(), m_depth.end(), kInfinity);
    m_occluders = 0;
}

float OcclusionBuffer::depthMargin(float depth) {
    // Window depth z = f/(f - n) (1 - n/w) changes by n/w^2 per unit of view depth w (at least), and a
    // 24-bit buffer resolves 2^-24: with n = 0.05, surfaces 1.2e-6 w^2 apart get different values. Eight
    // times that, plus a quarter block for the rounding of positions.
    return 0.25f + 1.0e-5f * depth * depth;
}

bool OcclusionBuffer::project(const glm::vec3& min, const glm::vec3& max, bool farToo, Projected& out) const {
    out.nearest = kInfinity;
    out.farthest = -kInfinity;
    const glm::vec2 size(static_cast<float>(m_width), static_cast<float>(m_height));
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 p((i & 1) != 0 ? max.x : min.x, (i & 2) != 0 ? max.y : min.y, (i & 4) != 0 ? max.z : min.z);
        const glm::vec4 clip = m_viewProjection * glm::vec4(p, 1.0f);
        if (!(clip.w > 0.0f && clip.z + clip.w > 0.0f)) return false; // not inside the near plane
        if (farToo && !(clip.w - clip.z > 0.0f)) return false;
        out.corner[i] = (glm::vec2(clip.x, clip.y) / clip.w * 0.5f + 0.5f) * size;
        out.nearest = std::min(out.nearest, clip.w);
        out.farthest = std::max(out.farthest, clip.w);
    }
    return true;
}

bool OcclusionBuffer::addOccluder(const glm::vec3& min, const glm::vec3& max) {
    Projected p;
    if (!project(min, max, true, p)) return false;
    std::array<glm::vec2, 16> hull;
    const int n = convexHull(p.corner, hull);
    // Eight corners make at most eight hull edges; rounding could let a nearly collinear corner into
    // both chains, and such a sliver is not worth drawing.
    if (n < 3 || n > 8) return false;
    // Edges as a x + b y + c >= 0 inside, (a, b) of unit length so that c is a distance in pixels.
    struct Edge {
        float a, b, c;
    };
    std::array<Edge, 8> edges;
    float yMin = kInfinity, yMax = -kInfinity;
    for (int i = 0; i < n; ++i) {
        const glm::vec2 from = hull[static_cast<std::size_t>(i)], to = hull[static_cast<std::size_t>((i + 1) % n)];
        const glm::vec2 d = to - from;
        const float length = std::sqrt(d.x * d.x + d.y * d.y);
        if (!(length > 0.0f)) return false;
        const float a = -d.y / length, b = d.x / length;
        edges[static_cast<std::size_t>(i)] = {a, b, -(a * from.x + b * from.y)};
        yMin = std::min(yMin, from.y);
        yMax = std::max(yMax, from.y);
    }
    const int rowFirst = ceilWithin(yMin, 0, m_height);
    const int rowLast = floorWithin(yMax, 0, m_height) - 1;
    bool drawn = false;
    for (int j = rowFirst; j <= rowLast; ++j) {
        // Pixel i of row j is [i, i + 1] x [j, j + 1]: inside every edge at its worst corner.
        float lo = 0.0f, hi = static_cast<float>(m_width - 1);
        for (int e = 0; e < n && lo <= hi; ++e) {
            const Edge& edge = edges[static_cast<std::size_t>(e)];
            const float k = edge.b * static_cast<float>(edge.b >= 0.0f ? j : j + 1) + edge.c - kInset;
            if (edge.a > 1e-6f) {
                lo = std::max(lo, std::ceil(-k / edge.a));
            } else if (edge.a < -1e-6f) {
                hi = std::min(hi, std::floor(-k / edge.a) - 1.0f);
            } else if (k < 0.0f) {
                hi = -1.0f;
            }
        }
        if (lo > hi) continue;
        float* row = m_depth.data() + static_cast<std::ptrdiff_t>(j) * m_width;
        for (int i = static_cast<int>(lo), last = static_cast<int>(hi); i <= last; ++i)
            row[i] = std::min(row[i], p.farthest);
        drawn = true;
    }
    if (drawn) ++m_occluders;
    return drawn;
}

bool OcclusionBuffer::hides(const glm::vec3& min, const glm::vec3& max) const {
    Projected p;
    if (m_occluders == 0 || !project(min, max, false, p)) return false;
    std::array<glm::vec2, 16> hull;
    const int n = convexHull(p.corner, hull);
    if (n < 1) return false;
    float yMin = kInfinity, yMax = -kInfinity;
    for (int i = 0; i < n; ++i) {
        yMin = std::min(yMin, hull[static_cast<std::size_t>(i)].y);
        yMax = std::max(yMax, hull[static_cast<std::size_t>(i)].y);
    }
    const int rowFirst = floorWithin(yMin - kInset, 0, m_height);
    const int rowLast = std::min(m_height - 1, floorWithin(yMax + kInset, -1, m_height));
    // A box whose hull touches no pixel (off the screen) has no fragment to draw: hidden too.
    for (int j = rowFirst; j <= rowLast; ++j) {
        // The silhouette's extent in x within the row's slab of y, widened by kInset on every side:
        // the pixels of the row that any of it touches.
        const float y0 = static_cast<float>(j) - kInset, y1 = static_cast<float>(j + 1) + kInset;
        float xMin = kInfinity, xMax = -kInfinity;
        for (int e = 0; e < n; ++e) {
            glm::vec2 a = hull[static_cast<std::size_t>(e)], b = hull[static_cast<std::size_t>((e + 1) % n)];
            if (a.y > b.y) std::swap(a, b);
            if (b.y < y0 || a.y > y1) continue;
            const auto xAt = [&](float y) { return b.y > a.y ? a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y) : a.x; };
            const float xa = a.y < y0 ? xAt(y0) : a.x, xb = b.y > y1 ? xAt(y1) : b.x;
            xMin = std::min({xMin, xa, xb});
            xMax = std::max({xMax, xa, xb});
        }
        if (xMin > xMax) continue;
        const int x0 = floorWithin(xMin - kInset, 0, m_width);
        const int x1 = std::min(m_width - 1, floorWithin(xMax + kInset, -1, m_width));
        if (!rowHides(j, x0, x1, p.nearest)) return false;
    }
    return true;
}

bool OcclusionBuffer::rowHides(int j, int x0, int x1, float nearest) const {
    const float* row = m_depth.data() + static_cast<std::ptrdiff_t>(j) * m_width;
    for (int x = x0; x <= x1; ++x) {
        if (!(row[x] + depthMargin(row[x]) < nearest)) return false;
    }
    return true;
}

bool OcclusionBuffer::hidesBounds(const glm::vec3& min, const glm::vec3& max) const {
    if (m_occluders == 0) return false;
    // Clip coordinates are affine in position: the corners are the first one plus the edge vectors.
    const glm::vec4 first = m_viewProjection * glm::vec4(min, 1.0f);
    const glm::vec3 extent = max - min;
    const std::array<glm::vec4, 3> edge{m_viewProjection[0] * extent.x, m_viewProjection[1] * extent.y,
                                        m_viewProjection[2] * extent.z};
    int corners = 0; // of the axes along which the box has extent, bit a for axis a
    for (int a = 0; a < 3; ++a)
        if (extent[a] != 0.0f) corners |= 1 << a;
    const glm::vec2 size(static_cast<float>(m_width), static_cast<float>(m_height));
    glm::vec2 low(kInfinity), high(-kInfinity);
    float nearest = kInfinity;
    for (int i = 0; i < 8; ++i) {
        if ((i & ~corners) != 0) continue; // the same corner as one with that bit clear
        glm::vec4 clip = first;
        for (int a = 0; a < 3; ++a)
            if ((i >> a & 1) != 0) clip += edge[static_cast<std::size_t>(a)];
        if (!(clip.w > 0.0f && clip.z + clip.w > 0.0f)) return false; // not inside the near plane
        const glm::vec2 pixel = (glm::vec2(clip.x, clip.y) / clip.w * 0.5f + 0.5f) * size;
        low = glm::min(low, pixel);
        high = glm::max(high, pixel);
        nearest = std::min(nearest, clip.w);
    }
    const int rowFirst = floorWithin(low.y - kInset, 0, m_height);
    const int rowLast = std::min(m_height - 1, floorWithin(high.y + kInset, -1, m_height));
    const int x0 = floorWithin(low.x - kInset, 0, m_width);
    const int x1 = std::min(m_width - 1, floorWithin(high.x + kInset, -1, m_width));
    for (int j = rowFirst; j <= rowLast; ++j) {
        if (!rowHides(j, x0, x1, nearest)) return false;
    }
    return true;
}

void SolidGrid::reset(const glm::ivec3& blocks, const glm::vec3& at) {
    if (blocks.x <= 0 || blocks.y <= 0 || blocks.z <= 0 || blocks.x % 32 != 0)
        throw std::invalid_argument("SolidGrid: the size must be positive and a multiple of 32 blocks along x");
    size = blocks;
    origin = at;
    rows.assign(static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z) * static_cast<std::size_t>(words()),
                0u);
}

int OcclusionBuffer::addSolidBlocks(const SolidGrid& grid, float maxDepth) {
    if (grid.size.x <= 0 || grid.size.y <= 0 || grid.size.z <= 0 || !(maxDepth > 0.0f)) return 0;
    // The point at view depth w on the ray through normalised device coordinates (nx, ny): affine in
    // w along the ray (between its points on the near and the far plane), and at a fixed w affine in
    // (nx, ny). So every ray is eye + w * dir(nx, ny), dir = d0 + nx * dx + ny * dy.
    const glm::dmat4 vp(m_viewProjection);
    const glm::dmat4 inverse = glm::inverse(vp);
    const auto pointAt = [&](double nx, double ny, double w) {
        glm::dvec4 a = inverse * glm::dvec4(nx, ny, -1.0, 1.0), b = inverse * glm::dvec4(nx, ny, 1.0, 1.0);
        const glm::dvec3 pa = glm::dvec3(a) / a.w, pb = glm::dvec3(b) / b.w;
        const double wa = (vp * glm::dvec4(pa, 1.0)).w, wb = (vp * glm::dvec4(pb, 1.0)).w;
        return pa + (w - wa) / (wb - wa) * (pb - pa);
    };
    // A perspective projection's far plane is a plane of constant view depth: nothing beyond it is drawn,
    // so no face there can stand in front of anything.
    const glm::dvec4 farCentre = inverse * glm::dvec4(0.0, 0.0, 1.0, 1.0);
    const double farDepth = (vp * glm::dvec4(glm::dvec3(farCentre) / farCentre.w, 1.0)).w;
    const glm::dvec3 eyeD = pointAt(0.0, 0.0, 0.0);
    if (!(farDepth > 0.0) || !std::isfinite(farDepth) || !std::isfinite(eyeD.x + eyeD.y + eyeD.z)) return 0;
    maxDepth = std::min(maxDepth, static_cast<float>(farDepth));
    const glm::dvec3 d0D = pointAt(0.0, 0.0, 1.0) - eyeD;
    const glm::vec3 d0(d0D), dx(pointAt(1.0, 0.0, 1.0) - eyeD - d0D), dy(pointAt(0.0, 1.0, 1.0) - eyeD - d0D);
    const glm::vec3 eye = glm::vec3(eyeD - glm::dvec3(grid.origin)); // in the grid's blocks
    const glm::ivec3 start(glm::floor(eye));
    const glm::ivec3 size = grid.size;
    if (glm::any(glm::lessThan(start, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(start, size)) ||
        grid.solid(start.x, start.y, start.z)) {
        return 0; // the eye must be in the grid's air
    }
    int top = -1; // the highest layer with a solid block: a ray above it going up meets none
    for (int y = size.y - 1; y >= 0 && top < 0; --y) {
        const std::uint32_t* first = grid.rows.data() + static_cast<std::ptrdiff_t>(y) * size.z * grid.words();
        if (std::any_of(first, first + static_cast<std::ptrdiff_t>(size.z) * grid.words(),
                        [](std::uint32_t r) { return r != 0; }))
            top = y;
    }
    if (top < 0) return 0;

    // Whether every block the box [lo, hi] touches is solid; the box widened by far more than the
    // rounding of its corners.
    const auto allSolid = [&](const glm::vec3& lo, const glm::vec3& hi) {
        const glm::ivec3 a(glm::floor(lo - 1e-3f)), b(glm::floor(hi + 1e-3f));
        if (glm::any(glm::lessThan(a, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(b, size))) return false;
        for (int y = a.y; y <= b.y; ++y)
            for (int z = a.z; z <= b.z; ++z)
                for (int x = a.x; x <= b.x; ++x)
                    if (!grid.solid(x, y, z)) return false;
        return true;
    };

    // One ray for each tile of kTile x kTile pixels, its pyramid the tile's: a quarter of the rays of
    // one a pixel, for a rim of a pixel less where a silhouette crosses a tile.
    constexpr int kTile = 2;
    const std::uint32_t* rows = grid.rows.data();
    const int strideZ = grid.words(), strideY = size.z * grid.words();
    int lowered = 0;
    const float w = static_cast<float>(m_width), h = static_cast<float>(m_height);
    for (int j0 = 0; j0 < m_height; j0 += kTile) {
        const int j1 = std::min(j0 + kTile, m_height);
        const float ny0 = 2.0f * (static_cast<float>(j0) - kInset) / h - 1.0f;
        const float ny1 = 2.0f * (static_cast<float>(j1) + kInset) / h - 1.0f;
        const float nyc = 0.5f * (ny0 + ny1);
        const glm::vec3 yLow = glm::min(ny0 * dy, ny1 * dy), yHigh = glm::max(ny0 * dy, ny1 * dy);
        for (int i0 = 0; i0 < m_width; i0 += kTile) {
            const int i1 = std::min(i0 + kTile, m_width);
            float limit = 0.0f; // no tile's pixel gains from a block deeper than its farthest value
            for (int j = j0; j < j1; ++j)
                for (int i = i0; i < i1; ++i)
                    limit = std::max(limit, m_depth[static_cast<std::size_t>(j) * static_cast<std::size_t>(m_width) +
                                                    static_cast<std::size_t>(i)]);
            limit = std::min(limit, maxDepth);
            const float nx0 = 2.0f * (static_cast<float>(i0) - kInset) / w - 1.0f;
            const float nx1 = 2.0f * (static_cast<float>(i1) + kInset) / w - 1.0f;
            const float nxc = 0.5f * (nx0 + nx1);
            // The pyramid's section at depth t lies in the box eye + t * [low, high] (t > 0).
            const glm::vec3 low = d0 + glm::min(nx0 * dx, nx1 * dx) + yLow;
            const glm::vec3 high = d0 + glm::max(nx0 * dx, nx1 * dx) + yHigh;
            const glm::vec3 dir = d0 + nxc * dx + nyc * dy;
            // The centre ray, block by block (Amanatides and Woo), in depth t.
            glm::ivec3 cell = start, step(0);
            glm::vec3 next(kInfinity), delta(kInfinity);
            for (int a = 0; a < 3; ++a) {
                if (dir[a] > 0.0f) {
                    step[a] = 1;
                    delta[a] = 1.0f / dir[a];
                    next[a] = (static_cast<float>(cell[a] + 1) - eye[a]) * delta[a];
                } else if (dir[a] < 0.0f) {
                    step[a] = -1;
                    delta[a] = -1.0f / dir[a];
                    next[a] = (eye[a] - static_cast<float>(cell[a])) * delta[a];
                }
            }
            float in = 0.0f;
            while (in < limit) {
                const int a = next.x < next.y ? (next.x < next.z ? 0 : 2) : (next.y < next.z ? 1 : 2);
                const float out = next[a];
                if ((rows[cell.y * strideY + cell.z * strideZ + (cell.x >> 5)] >> (cell.x & 31) & 1u) != 0) {
                    const float t = 0.5f * (in + out);
                    if (t < limit && allSolid(eye + t * low, eye + t * high)) {
                        for (int j = j0; j < j1; ++j) {
                            for (int i = i0; i < i1; ++i) {
                                float& d = m_depth[static_cast<std::size_t>(j) * static_cast<std::size_t>(m_width) +
                                                   static_cast<std::size_t>(i)];
                                if (t < d) {
                                    d = t;
                                    ++lowered;
                                }
                            }
                        }
                        break;
                    }
                }
                cell[a] += step[a]; // only this coordinate changed: the cell stays in the grid if it does
                if (cell[a] < 0 || cell[a] >= size[a] || (cell.y > top && step.y >= 0)) break;
                in = out;
                next[a] += delta[a];
            }
        }
    }
    if (lowered > 0) ++m_occluders;
    return lowered;
}

} // namespace render
