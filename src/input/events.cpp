#include "input/events.h"

namespace input {
namespace {

// Indexed by the enum value, so the order here is the GLFW order.
constexpr std::array<std::string_view, kGamepadAxisCount> kAxisNames{
    "left_x", "left_y", "right_x", "right_y", "left_trigger", "right_trigger",
};
constexpr std::array<std::string_view, kGamepadButtonCount> kButtonNames{
    "a",     "b",          "x",           "y",       "left_bumper", "right_bumper", "back",      "start",
    "guide", "left_thumb", "right_thumb", "dpad_up", "dpad_right",  "dpad_down",    "dpad_left",
};

template <typename Enum, std::size_t N>
std::optional<Enum> lookup(const std::array<std::string_view, N>& names, std::string_view name) {
    for (std::size_t i = 0; i < N; ++i)
        if (names[i] == name) return static_cast<Enum>(i);
    return std::nullopt;
}

template <std::size_t N>
std::string_view nameAt(const std::array<std::string_view, N>& names, int index) {
    if (index < 0 || static_cast<std::size_t>(index) >= N) return {};
    return names[static_cast<std::size_t>(index)];
}

} // namespace

std::optional<GamepadAxis> gamepadAxisFromName(std::string_view name) { return lookup<GamepadAxis>(kAxisNames, name); }

std::optional<GamepadButton> gamepadButtonFromName(std::string_view name) {
    return lookup<GamepadButton>(kButtonNames, name);
}

std::string_view gamepadAxisName(GamepadAxis axis) { return nameAt(kAxisNames, static_cast<int>(axis)); }

std::string_view gamepadButtonName(GamepadButton button) { return nameAt(kButtonNames, static_cast<int>(button)); }

} // namespace input
