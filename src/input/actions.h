// One tick of player intent, produced by input::InputMapper and consumed by game::tick. It is the
// only thing the game sees of the input devices: no key codes, no pixels, no pad axes.
// Held fields are true for every tick the control is down (and for the one tick after a tap shorter
// than a tick); edge fields are true for exactly one tick per press.
#pragma once
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace input {

struct Actions {
    glm::vec2 move{0.0f};                                      // x: strafe right (+), y: forward (+); length <= 1
    float yawDelta = 0.0f;                                     // degrees; + turns right (clockwise seen from above)
    float pitchDelta = 0.0f;                                   // degrees; + looks up
    bool jump = false;                                         // held (jump / fly up)
    bool descend = false;                                      // held (fly down)
    bool sprint = false;                                       // held
    bool place = false, breakBlock = false, pickBlock = false; // edges: one per press
    bool interact = false; // edge: open the panel of what the player looks at (E, d-pad up)
    bool carry = false;    // edge: pick up the hair ball looked at / put it down (Q, right stick click)
    bool toggleFly = false, togglePause = false, screenshot = false, toggleOverlay = false,
         toggleHelp = false; // edges
    int selectDelta = 0;     // hotbar steps (+ = next)
    int selectSlot = -1;     // 0..8 when a number key was pressed this tick
    // Absolute overrides from scripts. The game applies them before the deltas above: the deltas
    // hold only motion that arrived after the last absolute look.
    std::optional<glm::vec3> teleport;
    std::optional<glm::vec2> lookAbsolute; // yaw, pitch degrees
};

} // namespace input
