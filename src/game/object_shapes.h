// The solid shapes each object is drawn as and hit by, defined once: the ray that picks what a click acts
// on (targetOf) and the renderer (render/scene_renderer.cpp) both read this list, so what the crosshair
// shows is what the click hits. A pendulum set is its post, its two arms, its four rods and its four
// bobs; a hair ball is its sphere (its strands, drawn as lines, are not hit on their own).
#pragma once
#include <cstddef>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

namespace game {

struct GameState;
class PendulumSet;
class HairBall;

struct Shape {
    enum class Kind { Box, Sphere, Rod };
    Kind kind = Kind::Box;
    // Box: its corners lo and hi (axis-aligned). Sphere: a is the centre. Rod: a square prism from a to b.
    glm::vec3 a{0.0f}, b{0.0f};
    glm::vec3 side{1.0f, 0.0f, 0.0f}; // Rod: a unit vector perpendicular to b - a, the normal of two faces
    float radius = 0.0f;              // Sphere: radius. Rod: half its width.
    glm::vec3 colour{1.0f};
};

// A rod's frame, the same for the ray and for the triangles drawn: the unit vector from a to b, its length,
// and the two unit normals of its faces (side, and along x side).
struct RodFrame {
    glm::vec3 along, u, v;
    float length;
};
RodFrame rodFrame(const Shape& rod);

// The distance along the ray o + t d (d a unit vector, t >= 0) where it enters the shape; 0 from inside.
std::optional<float> rayShape(const glm::vec3& o, const glm::vec3& d, const Shape& shape);

constexpr float kPostHalfWidth = 0.08f; // m
constexpr float kArmHalfWidth = 0.04f;  // m
constexpr float kRodHalfWidth = 0.015f; // m

// The shapes of a set with its slots at the state drawn alpha of the way from the last tick to this one
// (1: the state the game holds now, the one a click acts on).
void appendPendulumSetShapes(const PendulumSet& set, double alpha, std::vector<Shape>& out);
Shape hairBallShape(const HairBall& ball, float alpha);

} // namespace game
