// The occlusion buffer (src/render/occlusion_buffer.h) is plain geometry: these tests need no GL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "render/occlusion_buffer.h"

namespace {

// The game's projection (70 degrees, 16:9, near 0.05), the camera at the origin looking along `forward`.
glm::mat4 viewProjection(glm::vec3 forward) {
    const glm::vec3 up = std::abs(forward.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::perspective(glm::radians(70.0f), 16.0f / 9.0f, 0.05f, 600.0f) *
           glm::lookAt(glm::vec3(0.0f), forward, up);
}

struct Box {
    glm::vec3 min, max;
};

// Where the ray from the origin through `direction` first enters the box (slab method): the ray
// parameter, or a negative value when it misses.
float entry(const Box& b, glm::vec3 direction) {
    float t0 = 0.0f, t1 = 1e30f;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(direction[a]) < 1e-12f) {
            if (b.min[a] > 0.0f || b.max[a] < 0.0f) return -1.0f;
            continue;
        }
        float near = b.min[a] / direction[a], far = b.max[a] / direction[a];
        if (near > far) std::swap(near, far);
        t0 = std::max(t0, near);
        t1 = std::min(t1, far);
    }
    return t0 <= t1 ? t0 : -1.0f;
}

} // namespace

// A wall 20 blocks ahead hides a box straight behind it, and nothing that peeks past its edge, stands in
// front of it, reaches through it, or crosses the near plane.
TEST(OcclusionBuffer, AWallHidesWhatIsStraightBehindItOnly) {
    render::OcclusionBuffer buffer;
    buffer.clear(viewProjection({0, 0, -1}));
    EXPECT_EQ(buffer.occluders(), 0);
    EXPECT_FALSE(buffer.hides({-1, -1, -41}, {1, 1, -39})) << "no occluder yet";
    ASSERT_TRUE(buffer.addOccluder({-10, -10, -21}, {10, 10, -20}));
    EXPECT_EQ(buffer.occluders(), 1);
    EXPECT_TRUE(buffer.hides({-1, -1, -41}, {1, 1, -39}));
    EXPECT_TRUE(buffer.hides({-15, -15, -80}, {15, 15, -60})) << "wider than the wall, but further";
    EXPECT_FALSE(buffer.hides({25, -1, -41}, {27, 1, -39})) << "beside the wall's silhouette";
    EXPECT_FALSE(buffer.hides({9, -1, -41}, {30, 1, -39})) << "partly beside it";
    EXPECT_FALSE(buffer.hides({-1, -1, -11}, {1, 1, -9})) << "in front of the wall";
    EXPECT_FALSE(buffer.hides({-1, -1, -25}, {1, 1, -15})) << "through the wall";
    EXPECT_FALSE(buffer.hides({-1, -1, -21.1f}, {1, 1, -20.9f})) << "nearer than the wall's far side";
    EXPECT_FALSE(buffer.hides({-1, -1, -30}, {1, 1, 5})) << "across the near plane";
    EXPECT_TRUE(buffer.hides({-1, 200, -41}, {1, 202, -39})) << "off the screen: nothing of it is drawn";
    EXPECT_FALSE(buffer.hides({-1, 200, 39}, {1, 202, 41})) << "behind the camera";
    EXPECT_FALSE(buffer.addOccluder({-10, -10, -5}, {10, 10, 5})) << "an occluder across the near plane";
    EXPECT_FALSE(buffer.addOccluder({-10, -10, -700}, {10, 10, -650})) << "beyond the far plane";
}

// A box behind the wall by less than the depth margin is not hidden: the depth buffer might order them
// either way.
TEST(OcclusionBuffer, KeepsTheDepthMargin) {
    render::OcclusionBuffer buffer;
    buffer.clear(viewProjection({0, 0, -1}));
    ASSERT_TRUE(buffer.addOccluder({-10, -10, -21}, {10, 10, -20}));
    const float margin = render::OcclusionBuffer::depthMargin(21.0f);
    EXPECT_GT(margin, 0.0f);
    EXPECT_FALSE(buffer.hides({-1, -1, -30}, {1, 1, -21.0f - 0.5f * margin}));
    EXPECT_TRUE(buffer.hides({-1, -1, -30}, {1, 1, -21.0f - 1.5f * margin}));
}

// Inner coverage: a wall across the whole view covers every pixel, with its farthest corner's depth; a
// thin post covers no pixel it only crosses in part.
TEST(OcclusionBuffer, CoversOnlyPixelsWhollyInsideASilhouette) {
    render::OcclusionBuffer buffer(160, 90);
    buffer.clear(viewProjection({0, 0, -1}));
    ASSERT_TRUE(buffer.addOccluder({-100, -100, -11}, {100, 100, -10}));
    for (int y = 0; y < buffer.height(); ++y)
        for (int x = 0; x < buffer.width(); ++x) ASSERT_FLOAT_EQ(buffer.depthAt(x, y), 11.0f) << x << ' ' << y;
    // A wall whose right edge falls 0.7 of the way across pixel column 100 covers that column's centre
    // but not the whole of it: a box behind it seen only in the rest of the column is not hidden.
    const float f = 1.0f / std::tan(glm::radians(35.0f)), aspect = 16.0f / 9.0f;
    const auto worldX = [&](float column, float depth) { return (column / 80.0f - 1.0f) * depth * aspect / f; };
    buffer.clear(viewProjection({0, 0, -1}));
    ASSERT_TRUE(buffer.addOccluder({-10, -10, -21}, {worldX(100.7f, 20.0f), 10, -20}));
    EXPECT_TRUE(std::isinf(buffer.depthAt(100, 45)));
    EXPECT_FLOAT_EQ(buffer.depthAt(99, 45), 21.0f);
    EXPECT_FALSE(buffer.hides({worldX(100.72f, 40.0f), -1, -40.5f}, {worldX(100.85f, 40.0f), 1, -40}));
    EXPECT_TRUE(buffer.hides({worldX(99.2f, 40.0f), -1, -40.5f}, {worldX(99.5f, 40.0f), 1, -40}))
        << "precondition: a box as thin in the pixel before is hidden";
    buffer.clear(viewProjection({0, 0, -1}));
    // 0.02 blocks wide at 20 blocks: about a tenth of a pixel of this buffer (a pixel spans 0.18 blocks there).
    EXPECT_FALSE(buffer.addOccluder({-0.01f, -10, -21}, {0.01f, 10, -20}));
    EXPECT_EQ(buffer.occluders(), 0);
}

// The promise itself, on random scenes: whenever the buffer says a box is hidden, the ray from the
// camera to any point of the box that lies in view enters some occluder nearer than that point.
TEST(OcclusionBuffer, EveryRayToAHiddenBoxMeetsAnOccluderFirst) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto between = [&](float a, float b) { return a + (b - a) * unit(rng); };
    int hidden = 0, shown = 0, raysChecked = 0;
    for (int scene = 0; scene < 200; ++scene) {
        const float yaw = between(0.0f, 6.2832f), pitch = between(-0.6f, 0.6f);
        const glm::vec3 forward(std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw));
        const glm::mat4 vp = viewProjection(forward);
        const glm::vec3 side = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
        const auto placed = [&](float distance, float spread, glm::vec3 size) {
            const glm::vec3 centre = forward * distance + side * between(-spread, spread) * distance +
                                     glm::vec3(0, between(-spread, spread) * distance, 0);
            return Box{centre - size * 0.5f, centre + size * 0.5f};
        };
        render::OcclusionBuffer buffer;
        buffer.clear(vp);
        std::vector<Box> occluders;
        for (int i = 0; i < 40; ++i) {
            const Box b =
                placed(between(4.0f, 40.0f), 0.6f, {between(2.0f, 24.0f), between(2.0f, 24.0f), between(2.0f, 24.0f)});
            if (buffer.addOccluder(b.min, b.max)) occluders.push_back(b);
        }
        for (int i = 0; i < 60; ++i) {
            const Box b =
                placed(between(10.0f, 120.0f), 0.5f, {between(0.5f, 8.0f), between(0.5f, 8.0f), between(0.5f, 8.0f)});
            if (!buffer.hides(b.min, b.max)) {
                ++shown;
                continue;
            }
            ++hidden;
            for (int k = 0; k < 64; ++k) {
                const glm::vec3 point =
                    k < 8 ? glm::vec3((k & 1) != 0 ? b.max.x : b.min.x, (k & 2) != 0 ? b.max.y : b.min.y,
                                      (k & 4) != 0 ? b.max.z : b.min.z)
                          : glm::mix(b.min, b.max, glm::vec3(unit(rng), unit(rng), unit(rng)));
                const glm::vec4 clip = vp * glm::vec4(point, 1.0f);
                if (std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w) continue; // not in view
                ++raysChecked;
                float nearest = 1e30f;
                for (const Box& o : occluders) {
                    const float t = entry(o, point);
                    if (t >= 0.0f) nearest = std::min(nearest, t);
                }
                // t = 1 is the point itself: the ray must enter an occluder before reaching it.
                ASSERT_LT(nearest, 1.0f) << "scene " << scene << ": a ray reaches a hidden box unblocked";
            }
        }
    }
    EXPECT_GT(hidden, 100) << "precondition: the scenes hide boxes";
    EXPECT_GT(shown, 100) << "precondition: and show some";
    EXPECT_GT(raysChecked, 1000);
}
