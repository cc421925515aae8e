#include "input/keys.h"

#include <array>
#include <utility>

namespace input {
namespace {

struct KeyEntry {
    std::string_view name;
    int code;
};

// The full GLFW 3.3 key list, in code order. Spelled out rather than generated so that a reader can
// check any entry against glfw3.h at a glance.
constexpr std::array kKeys{
    KeyEntry{"SPACE", 32},
    KeyEntry{"APOSTROPHE", 39},
    KeyEntry{"COMMA", 44},
    KeyEntry{"MINUS", 45},
    KeyEntry{"PERIOD", 46},
    KeyEntry{"SLASH", 47},
    KeyEntry{"0", 48},
    KeyEntry{"1", 49},
    KeyEntry{"2", 50},
    KeyEntry{"3", 51},
    KeyEntry{"4", 52},
    KeyEntry{"5", 53},
    KeyEntry{"6", 54},
    KeyEntry{"7", 55},
    KeyEntry{"8", 56},
    KeyEntry{"9", 57},
    KeyEntry{"SEMICOLON", 59},
    KeyEntry{"EQUAL", 61},
    KeyEntry{"A", 65},
    KeyEntry{"B", 66},
    KeyEntry{"C", 67},
    KeyEntry{"D", 68},
    KeyEntry{"E", 69},
    KeyEntry{"F", 70},
    KeyEntry{"G", 71},
    KeyEntry{"H", 72},
    KeyEntry{"I", 73},
    KeyEntry{"J", 74},
    KeyEntry{"K", 75},
    KeyEntry{"L", 76},
    KeyEntry{"M", 77},
    KeyEntry{"N", 78},
    KeyEntry{"O", 79},
    KeyEntry{"P", 80},
    KeyEntry{"Q", 81},
    KeyEntry{"R", 82},
    KeyEntry{"S", 83},
    KeyEntry{"T", 84},
    KeyEntry{"U", 85},
    KeyEntry{"V", 86},
    KeyEntry{"W", 87},
    KeyEntry{"X", 88},
    KeyEntry{"Y", 89},
    KeyEntry{"Z", 90},
    KeyEntry{"LEFT_BRACKET", 91},
    KeyEntry{"BACKSLASH", 92},
    KeyEntry{"RIGHT_BRACKET", 93},
    KeyEntry{"GRAVE_ACCENT", 96},
    KeyEntry{"WORLD_1", 161},
    KeyEntry{"WORLD_2", 162},
    KeyEntry{"ESCAPE", 256},
    KeyEntry{"ENTER", 257},
    KeyEntry{"TAB", 258},
    KeyEntry{"BACKSPACE", 259},
    KeyEntry{"INSERT", 260},
    KeyEntry{"DELETE", 261},
    KeyEntry{"RIGHT", 262},
    KeyEntry{"LEFT", 263},
    KeyEntry{"DOWN", 264},
    KeyEntry{"UP", 265},
    KeyEntry{"PAGE_UP", 266},
    KeyEntry{"PAGE_DOWN", 267},
    KeyEntry{"HOME", 268},
    KeyEntry{"END", 269},
    KeyEntry{"CAPS_LOCK", 280},
    KeyEntry{"SCROLL_LOCK", 281},
    KeyEntry{"NUM_LOCK", 282},
    KeyEntry{"PRINT_SCREEN", 283},
    KeyEntry{"PAUSE", 284},
    KeyEntry{"F1", 290},
    KeyEntry{"F2", 291},
    KeyEntry{"F3", 292},
    KeyEntry{"F4", 293},
    KeyEntry{"F5", 294},
    KeyEntry{"F6", 295},
    KeyEntry{"F7", 296},
    KeyEntry{"F8", 297},
    KeyEntry{"F9", 298},
    KeyEntry{"F10", 299},
    KeyEntry{"F11", 300},
    KeyEntry{"F12", 301},
    KeyEntry{"F13", 302},
    KeyEntry{"F14", 303},
    KeyEntry{"F15", 304},
    KeyEntry{"F16", 305},
    KeyEntry{"F17", 306},
    KeyEntry{"F18", 307},
    KeyEntry{"F19", 308},
    KeyEntry{"F20", 309},
    KeyEntry{"F21", 310},
    KeyEntry{"F22", 311},
    KeyEntry{"F23", 312},
    KeyEntry{"F24", 313},
    KeyEntry{"F25", 314},
    KeyEntry{"KP_0", 320},
    KeyEntry{"KP_1", 321},
    KeyEntry{"KP_2", 322},
    KeyEntry{"KP_3", 323},
    KeyEntry{"KP_4", 324},
    KeyEntry{"KP_5", 325},
    KeyEntry{"KP_6", 326},
    KeyEntry{"KP_7", 327},
    KeyEntry{"KP_8", 328},
    KeyEntry{"KP_9", 329},
    KeyEntry{"KP_DECIMAL", 330},
    KeyEntry{"KP_DIVIDE", 331},
    KeyEntry{"KP_MULTIPLY", 332},
    KeyEntry{"KP_SUBTRACT", 333},
    KeyEntry{"KP_ADD", 334},
    KeyEntry{"KP_ENTER", 335},
    KeyEntry{"KP_EQUAL", 336},
    KeyEntry{"LEFT_SHIFT", 340},
    KeyEntry{"LEFT_CONTROL", 341},
    KeyEntry{"LEFT_ALT", 342},
    KeyEntry{"LEFT_SUPER", 343},
    KeyEntry{"RIGHT_SHIFT", 344},
    KeyEntry{"RIGHT_CONTROL", 345},
    KeyEntry{"RIGHT_ALT", 346},
    KeyEntry{"RIGHT_SUPER", 347},
    KeyEntry{"MENU", 348},
};

// The lookups below rely on this; a mistyped entry fails the build instead of a test.
constexpr bool strictlyIncreasing() {
    for (std::size_t i = 1; i < kKeys.size(); ++i)
        if (kKeys[i - 1].code >= kKeys[i].code) return false;
    return kKeys.front().code >= 0 && kKeys.back().code == kKeyLast;
}
static_assert(strictlyIncreasing(), "key table must be sorted by code and end at GLFW_KEY_LAST");

} // namespace

std::optional<int> keyFromName(std::string_view name) {
    // 120 short strings, looked up only while parsing scripts and config: a linear scan is plenty.
    for (const KeyEntry& entry : kKeys)
        if (entry.name == name) return entry.code;
    return std::nullopt;
}

std::string_view keyName(int key) {
    for (const KeyEntry& entry : kKeys) {
        if (entry.code == key) return entry.name;
        if (entry.code > key) break;
    }
    return {};
}

} // namespace input
