#include "input/mapper.h"

#include "input/action_table.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>

#include <glm/geometric.hpp>

namespace input {
namespace {

constexpr std::size_t index(GamepadAxis axis) { return static_cast<std::size_t>(axis); }
constexpr std::size_t index(GamepadButton button) { return static_cast<std::size_t>(button); }

// Hotbar steps per tick from scroll are bounded so a bogus scroll value cannot overflow an int.
constexpr float kMaxPendingScroll = 1000.0f;

// Pads and scripts should give -1..1, but a NaN from a broken driver must not poison the player's state.
float sanitizeAxis(float value, float rest) {
    if (!std::isfinite(value)) return rest;
    return std::clamp(value, -1.0f, 1.0f);
}

// Radial rather than per-axis so that diagonals keep their direction, rescaled so that the output
// rises from 0 at the deadzone edge instead of jumping to the deadzone's size.
glm::vec2 radialDeadzone(glm::vec2 stick, float deadzone) {
    const float dz = std::isfinite(deadzone) ? std::clamp(deadzone, 0.0f, 1.0f) : 0.0f;
    const float length = glm::length(stick);
    if (length <= dz || dz >= 1.0f) return glm::vec2(0.0f);
    // Square-gated sticks reach length sqrt(2) in the corners; full deflection is 1 in every direction.
    const float scaled = (std::min(length, 1.0f) - dz) / (1.0f - dz);
    return stick * (scaled / length);
}

// One step of a trigger's hysteresis on 0..1 travel. Returns true on the pull that crosses the press
// threshold from below; a trigger resting between the thresholds neither fires nor re-arms.
bool stepTrigger(float axis, bool& held, const InputConfig& config) {
    const float travel = (sanitizeAxis(axis, -1.0f) + 1.0f) * 0.5f;
    const float press = std::isfinite(config.triggerPress) ? std::clamp(config.triggerPress, 0.0f, 1.0f) : 0.6f;
    // A release threshold above the press threshold would let a steady trigger fire every tick.
    const float release = std::isfinite(config.triggerRelease) ? std::clamp(config.triggerRelease, 0.0f, press) : 0.0f;
    if (!held && travel >= press) {
        held = true;
        return true;
    }
    if (held && travel < release) held = false;
    return false;
}

glm::vec2 clampLength(glm::vec2 v) {
    const float length = glm::length(v);
    return length > 1.0f ? v / length : v;
}

template <typename... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};
template <typename... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

} // namespace

GamepadMapping mapGamepad(const GamepadState& now, const GamepadMemory& previous, const InputConfig& config, float dt) {
    GamepadMapping out;
    if (!now.connected) return out;

    auto axis = [&](GamepadAxis a) { return sanitizeAxis(now.axis(a), 0.0f); };
    // An unbound (Count) or out-of-range button is never down.
    auto down = [&](GamepadButton b) { return index(b) < kGamepadButtonCount && now.button(b); };
    auto pressed = [&](GamepadButton b) { return down(b) && !previous.prevButtons[index(b)]; };
    Actions& actions = out.actions;
    const GamepadBindings& pad = config.pad;

    // GLFW's +y is down; the game's move.y is forward.
    actions.move =
        clampLength(radialDeadzone({axis(GamepadAxis::LeftX), -axis(GamepadAxis::LeftY)}, config.stickDeadzone));
    const glm::vec2 look =
        radialDeadzone({axis(GamepadAxis::RightX), -axis(GamepadAxis::RightY)}, config.stickDeadzone);
    const float step = config.lookStickDegreesPerSecond * (std::isfinite(dt) && dt > 0.0f ? dt : 0.0f);
    actions.yawDelta = look.x * step;
    actions.pitchDelta = (config.invertY ? -look.y : look.y) * step;

    for (const PadAction& a : kPadActions) {
        if (a.action) actions.*a.action = a.trigger == Trigger::Held ? down(pad.*a.button) : pressed(pad.*a.button);
    }
    actions.selectDelta += pressed(pad.selectNext) ? 1 : 0;
    actions.selectDelta -= pressed(pad.selectPrev) ? 1 : 0;

    out.memory.leftTriggerHeld = previous.leftTriggerHeld;
    out.memory.rightTriggerHeld = previous.rightTriggerHeld;
    if (stepTrigger(now.axis(GamepadAxis::LeftTrigger), out.memory.leftTriggerHeld, config)) actions.selectDelta -= 1;
    if (stepTrigger(now.axis(GamepadAxis::RightTrigger), out.memory.rightTriggerHeld, config)) actions.selectDelta += 1;
    out.memory.prevButtons = now.buttons;
    return out;
}

InputMapper::InputMapper(InputConfig config) : m_config(config) {}

bool InputMapper::keyHeld(int key) const {
    if (key < 0 || key > kKeyLast) return false;
    const auto k = static_cast<std::size_t>(key);
    return m_keyDown[k] || m_keyPressed[k];
}

bool InputMapper::keyPressed(int key) const {
    return key >= 0 && key <= kKeyLast && m_keyPressed[static_cast<std::size_t>(key)];
}

void InputMapper::handle(const InputEvent& event) {
    // A gamepad event changes one entry of the pad's state (with `change`); the whole state, marked connected,
    // then applies as setGamepadState's would.
    const auto changePad = [&](const auto& change) {
        GamepadState next = m_pad;
        next.connected = true;
        change(next);
        applyGamepadState(next);
    };
    std::visit(Overloaded{
                   [&](const KeyEvent& e) {
                       // GLFW_KEY_UNKNOWN (-1) and anything past GLFW_KEY_LAST carry no binding.
                       if (e.key < 0 || e.key > kKeyLast) return;
                       const auto k = static_cast<std::size_t>(e.key);
                       if (e.down && !m_keyDown[k]) {
                           m_keyPressed[k] = true;
                           if (e.key >= key::Digit1 && e.key <= key::Digit9) m_selectSlot = e.key - key::Digit1;
                       }
                       m_keyDown[k] = e.down;
                   },
                   [&](const MouseMoveEvent& e) {
                       if (std::isfinite(e.dx) && std::isfinite(e.dy)) m_mouseDelta += glm::vec2(e.dx, e.dy);
                   },
                   [&](const MouseButtonEvent& e) {
                       const auto b = static_cast<std::size_t>(e.button);
                       if (b >= kMouseButtons) return;
                       if (e.down && !m_mouseDown[b]) m_mousePressed[b] = true;
                       m_mouseDown[b] = e.down;
                   },
                   [&](const ScrollEvent& e) {
                       if (std::isfinite(e.dy))
                           m_scroll = std::clamp(m_scroll + e.dy, -kMaxPendingScroll, kMaxPendingScroll);
                   },
                   [&](const GamepadAxisEvent& e) {
                       if (index(e.axis) >= kGamepadAxisCount) return;
                       changePad([&](GamepadState& next) { next.axes[index(e.axis)] = e.value; });
                   },
                   [&](const GamepadButtonEvent& e) {
                       if (index(e.button) >= kGamepadButtonCount) return;
                       changePad([&](GamepadState& next) { next.buttons[index(e.button)] = e.down; });
                   },
                   [&](const TeleportEvent& e) { m_teleport = e.position; },
                   [&](const LookEvent& e) {
                       // Motion before an absolute look is superseded by it; only later motion still applies.
                       m_lookAbsolute = glm::vec2(e.yawDeg, e.pitchDeg);
                       m_mouseDelta = glm::vec2(0.0f);
                   },
                   [&](const ActionsEvent& e) { m_recorded = e.actions; },
               },
               event);
}

void InputMapper::applyGamepadState(const GamepadState& next) {
    for (std::size_t i = 0; i < kGamepadButtonCount; ++i)
        if (next.connected && next.buttons[i] && !(m_pad.connected && m_pad.buttons[i])) m_padPressed[i] = true;
    if (next.connected) {
        if (stepTrigger(next.axis(GamepadAxis::LeftTrigger), m_leftTriggerHeld, m_config)) m_triggerSteps -= 1;
        if (stepTrigger(next.axis(GamepadAxis::RightTrigger), m_rightTriggerHeld, m_config)) m_triggerSteps += 1;
    } else {
        // Unplugging mid-pull must not leave the trigger disarmed when the pad comes back.
        m_leftTriggerHeld = m_rightTriggerHeld = false;
    }
    m_pad = next;
}

void InputMapper::setGamepadState(const GamepadState& state) { applyGamepadState(state); }

const GamepadState& InputMapper::gamepad() const { return m_pad; }

glm::vec2 InputMapper::pendingLook() const {
    const float s = m_config.mouseDegreesPerPixel;
    // Screen +y is down; the game's +pitch is up.
    const float pitch = -m_mouseDelta.y * s;
    return {m_mouseDelta.x * s, m_config.invertY ? -pitch : pitch};
}

Actions InputMapper::takeTickActions(float dt) {
    Actions actions;
    const Bindings& b = m_config.keys;
    auto axisFromKeys = [&](int positive, int negative) {
        return (keyHeld(positive) ? 1.0f : 0.0f) - (keyHeld(negative) ? 1.0f : 0.0f);
    };
    const glm::vec2 keyMove{axisFromKeys(b.right, b.left), axisFromKeys(b.forward, b.back)};
    const glm::vec2 mouseLook = pendingLook();

    // The pad is seen as "down" for any button pressed since the last tick, with that press as its edge:
    // a tap between ticks both fires and holds for one tick, exactly like a key.
    GamepadState padView = m_pad;
    GamepadMemory padMemory;
    padMemory.leftTriggerHeld = m_leftTriggerHeld;
    padMemory.rightTriggerHeld = m_rightTriggerHeld;
    for (std::size_t i = 0; i < kGamepadButtonCount; ++i) {
        padView.buttons[i] = padView.buttons[i] || m_padPressed[i];
        padMemory.prevButtons[i] = !m_padPressed[i];
    }
    // Trigger pulls were already counted per update (m_triggerSteps) and the held flags match m_pad, so
    // mapGamepad finds no new trigger edge here.
    const Actions pad = mapGamepad(padView, padMemory, m_config, dt).actions;

    actions.move = clampLength(keyMove + pad.move);
    actions.yawDelta = mouseLook.x + pad.yawDelta;
    actions.pitchDelta = mouseLook.y + pad.pitchDelta;
    // The mouse buttons are fixed; every bound key ORs into what the pad asked for.
    actions.breakBlock = m_mousePressed[static_cast<std::size_t>(MouseButton::Left)] || pad.breakBlock;
    actions.place = m_mousePressed[static_cast<std::size_t>(MouseButton::Right)] || pad.place;
    actions.pickBlock = m_mousePressed[static_cast<std::size_t>(MouseButton::Middle)] || pad.pickBlock;
    for (const KeyAction& a : kKeyActions) {
        if (!a.action) continue;
        const bool key = a.trigger == Trigger::Held ? keyHeld(b.*a.key) : keyPressed(b.*a.key);
        actions.*a.action = key || pad.*a.action;
    }
    // Wheel up (+dy) goes to the previous slot. Whole notches only; a trackpad's fractions carry over.
    const float notches = std::trunc(m_scroll);
    m_scroll -= notches;
    actions.selectDelta = -static_cast<int>(notches) + pad.selectDelta + m_triggerSteps;
    actions.selectSlot = m_selectSlot;
    actions.teleport = m_teleport;
    actions.lookAbsolute = m_lookAbsolute;

    // A recorded tick replaces what the devices said (which is still consumed above, so it does not carry over).
    if (m_recorded) {
        actions = *m_recorded;
        m_recorded.reset();
    }
    m_keyPressed.fill(false);
    m_mousePressed.fill(false);
    m_padPressed.fill(false);
    m_mouseDelta = glm::vec2(0.0f);
    m_triggerSteps = 0;
    m_selectSlot = -1;
    m_teleport.reset();
    m_lookAbsolute.reset();
    return actions;
}

void InputMapper::releaseAll() {
    m_keyDown.fill(false);
    m_mouseDown.fill(false);
    m_mouseDelta = glm::vec2(0.0f);
    m_scroll = 0.0f;
    GamepadState rest;
    rest.connected = m_pad.connected;
    applyGamepadState(rest);
}

InputConfig& InputMapper::config() { return m_config; }

} // namespace input
