// Keyboard key codes and their names, for bindings and the headless script format.
// Codes are plain ints whose values equal GLFW's GLFW_KEY_* values, so the window layer passes GLFW
// codes straight through; this layer must never include GLFW (the input library has no GLFW on its
// include path). Names are GLFW's macro names without the GLFW_KEY_ prefix ("SPACE", "LEFT_SHIFT").
#pragma once
#include <optional>
#include <string_view>

namespace input {

// GLFW_KEY_LAST: every valid key code lies in 0..kKeyLast. GLFW reports unknown keys as -1.
inline constexpr int kKeyLast = 348;

// Exact, case-sensitive GLFW spelling; nullopt for anything else.
std::optional<int> keyFromName(std::string_view name);
// Empty for codes that are not GLFW keys.
std::string_view keyName(int key);

namespace key {
// Only the keys that default bindings, the mapper or tests refer to by name; any other key is still
// reachable through keyFromName.
inline constexpr int Space = 32;
inline constexpr int Digit0 = 48, Digit1 = 49, Digit2 = 50, Digit3 = 51, Digit4 = 52;
inline constexpr int Digit5 = 53, Digit6 = 54, Digit7 = 55, Digit8 = 56, Digit9 = 57;
inline constexpr int A = 65, D = 68, E = 69, F = 70, Q = 81, R = 82, S = 83, T = 84, W = 87;
inline constexpr int Escape = 256, Enter = 257, Tab = 258;
inline constexpr int Right = 262, Left = 263, Down = 264, Up = 265;
inline constexpr int PageUp = 266, PageDown = 267, Home = 268, End = 269;
inline constexpr int F1 = 290, F2 = 291, F3 = 292;
inline constexpr int LeftShift = 340, LeftControl = 341, LeftAlt = 342, LeftSuper = 343;
inline constexpr int RightShift = 344, RightControl = 345, RightAlt = 346, RightSuper = 347;
} // namespace key

} // namespace input
