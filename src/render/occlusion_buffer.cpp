#include "render/occlusion_buffer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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
        const float* row = m_depth.data() + static_cast<std::ptrdiff_t>(j) * m_width;
        for (int x = x0; x <= x1; ++x) {
            if (!(row[x] + depthMargin(row[x]) < p.nearest)) return false;
        }
    }
    return true;
}

} // namespace render
