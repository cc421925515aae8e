#include "game/object_shapes.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "game/hair_ball.h"
#include "game/pendulum_set.h"

namespace game {

namespace {

// Slab test of a ray against an axis-aligned box; returns the entry distance (0 from inside).
std::optional<float> rayBox(const glm::vec3& o, const glm::vec3& d, const glm::vec3& lo, const glm::vec3& hi) {
    float t0 = 0.0f, t1 = 1e30f;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12f) {
            if (o[a] < lo[a] || o[a] > hi[a]) return std::nullopt;
            continue;
        }
        float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return std::nullopt;
    }
    return t0;
}

std::optional<float> raySphere(const glm::vec3& o, const glm::vec3& d, const glm::vec3& c, float r) {
    const glm::vec3 oc = o - c;
    const float b = glm::dot(oc, d), cc = glm::dot(oc, oc) - r * r;
    const float disc = b * b - cc;
    if (disc < 0.0f) return std::nullopt;
    const float t = -b - std::sqrt(disc);
    if (t >= 0.0f) return t;
    return cc <= 0.0f ? std::optional<float>(0.0f) : std::nullopt; // inside
}

} // namespace

RodFrame rodFrame(const Shape& rod) {
    RodFrame f{};
    const glm::vec3 d = rod.b - rod.a;
    f.length = glm::length(d);
    f.along = f.length > 0.0f ? d / f.length : glm::vec3(0.0f, -1.0f, 0.0f);
    f.u = glm::normalize(rod.side - f.along * glm::dot(rod.side, f.along));
    f.v = glm::cross(f.along, f.u);
    return f;
}

std::optional<float> rayShape(const glm::vec3& o, const glm::vec3& d, const Shape& shape) {
    switch (shape.kind) {
    case Shape::Kind::Box:
        return rayBox(o, d, shape.a, shape.b);
    case Shape::Kind::Sphere:
        return raySphere(o, d, shape.a, shape.radius);
    case Shape::Kind::Rod: {
        // The same slab test in the rod's own frame, where it is a box; distances are kept (the frame is
        // orthonormal).
        const RodFrame f = rodFrame(shape);
        const glm::vec3 rel = o - shape.a;
        const glm::vec3 lo(0.0f, -shape.radius, -shape.radius), hi(f.length, shape.radius, shape.radius);
        return rayBox({glm::dot(rel, f.along), glm::dot(rel, f.u), glm::dot(rel, f.v)},
                      {glm::dot(d, f.along), glm::dot(d, f.u), glm::dot(d, f.v)}, lo, hi);
    }
    }
    return std::nullopt;
}

void appendPendulumSetShapes(const PendulumSet& set, double alpha, std::vector<Shape>& out) {
    const glm::vec3 wood(0.55f, 0.40f, 0.25f);
    const glm::vec3 foot = glm::vec3(set.base()) + glm::vec3(0.5f, 0.0f, 0.5f);
    const float top = set.postHeight();
    const float arm = PendulumSet::kArmLength;
    const float post = kPostHalfWidth, half = kArmHalfWidth;
    // A wooden box between the corners `lo` and `hi`, given relative to the foot of the post.
    const auto woodBox = [&](const glm::vec3& lo, const glm::vec3& hi) {
        out.push_back({Shape::Kind::Box, foot + lo, foot + hi, {1.0f, 0.0f, 0.0f}, 0.0f, wood});
    };
    // The post, reaching a little above the arms, and the two arms crossing at its top.
    woodBox({-post, 0.0f, -post}, {post, top + 0.06f, post});
    woodBox({-arm, top - half, -half}, {arm, top + half, half});
    woodBox({-half, top - half, -arm}, {half, top + half, arm});
    for (int i = 0; i < kPendulumSlots; ++i) {
        const physics::PendulumState s = set.drawnState(i, alpha);
        const glm::vec3 pivot = set.pivot(i);
        const glm::vec3 bob = set.bobPosition(i, s.theta);
        // The rod swings in the vertical plane of its arm: the plane's normal is always across it.
        const glm::vec3 across = glm::cross(set.swingAxis(i), glm::vec3(0.0f, 1.0f, 0.0f));
        out.push_back({Shape::Kind::Rod, pivot, bob, across, kRodHalfWidth, glm::vec3(0.85f)});
        const glm::vec3 colour =
            set.diverged(i) ? glm::vec3(0.25f) : methodColour(set.def().methods[static_cast<std::size_t>(i)]);
        out.push_back({Shape::Kind::Sphere, bob, bob, across, PendulumSet::kBobRadius, colour});
    }
}

Shape hairBallShape(const HairBall& ball, float alpha) {
    const glm::vec3 centre = ball.previousCentre() + (ball.centre() - ball.previousCentre()) * alpha;
    return {Shape::Kind::Sphere, centre, centre, {1.0f, 0.0f, 0.0f}, ball.def().radius, ball.def().colour * 0.8f};
}

} // namespace game
