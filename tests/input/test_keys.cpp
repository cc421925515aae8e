#include <climits>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "input/keys.h"

namespace {

TEST(Keys, DocumentedGlfwValues) {
    // Values from glfw3.h; the window passes GLFW codes straight through, so these must match exactly.
    const std::pair<const char*, int> expected[] = {
        {"SPACE", 32},
        {"APOSTROPHE", 39},
        {"COMMA", 44},
        {"SLASH", 47},
        {"0", 48},
        {"9", 57},
        {"SEMICOLON", 59},
        {"EQUAL", 61},
        {"A", 65},
        {"W", 87},
        {"Z", 90},
        {"LEFT_BRACKET", 91},
        {"GRAVE_ACCENT", 96},
        {"WORLD_1", 161},
        {"WORLD_2", 162},
        {"ESCAPE", 256},
        {"ENTER", 257},
        {"TAB", 258},
        {"BACKSPACE", 259},
        {"INSERT", 260},
        {"DELETE", 261},
        {"RIGHT", 262},
        {"LEFT", 263},
        {"DOWN", 264},
        {"UP", 265},
        {"PAGE_UP", 266},
        {"PAGE_DOWN", 267},
        {"HOME", 268},
        {"END", 269},
        {"CAPS_LOCK", 280},
        {"PAUSE", 284},
        {"F1", 290},
        {"F12", 301},
        {"F25", 314},
        {"KP_0", 320},
        {"KP_5", 325},
        {"KP_9", 329},
        {"KP_EQUAL", 336},
        {"LEFT_SHIFT", 340},
        {"LEFT_CONTROL", 341},
        {"LEFT_ALT", 342},
        {"LEFT_SUPER", 343},
        {"RIGHT_SHIFT", 344},
        {"RIGHT_CONTROL", 345},
        {"RIGHT_ALT", 346},
        {"RIGHT_SUPER", 347},
        {"MENU", 348},
    };
    for (const auto& [name, code] : expected) {
        EXPECT_EQ(input::keyFromName(name), code) << name;
        EXPECT_EQ(input::keyName(code), name) << code;
    }
}

TEST(Keys, EveryNamedCodeRoundTripsAndNamesAreUnique) {
    std::set<std::string> names;
    for (int code = -1; code <= input::kKeyLast + 1; ++code) {
        const std::string_view name = input::keyName(code);
        if (name.empty()) continue;
        EXPECT_EQ(input::keyFromName(name), code) << name;
        EXPECT_TRUE(names.insert(std::string(name)).second) << "duplicate " << name;
    }
    EXPECT_EQ(names.size(), 120u); // the whole GLFW 3.3 key list
}

TEST(Keys, UnknownNamesAndCodes) {
    for (const char* bad : {"", "space", "Space", "w", "GLFW_KEY_SPACE", "F0", "F26", "KP_10", " W", "W ", "LEFT SHIFT",
                            "UNKNOWN", "LAST", "-1"})
        EXPECT_FALSE(input::keyFromName(bad).has_value()) << "'" << bad << "'";
    for (int code : {-1, 0, 31, 33, 58, 255, 349, 1000, INT_MIN, INT_MAX})
        EXPECT_TRUE(input::keyName(code).empty()) << code;
}

TEST(Keys, ConstantsMatchTheirNames) {
    namespace k = input::key;
    const std::pair<const char*, int> constants[] = {
        {"SPACE", k::Space},
        {"0", k::Digit0},
        {"1", k::Digit1},
        {"9", k::Digit9},
        {"A", k::A},
        {"D", k::D},
        {"E", k::E},
        {"F", k::F},
        {"Q", k::Q},
        {"S", k::S},
        {"W", k::W},
        {"ESCAPE", k::Escape},
        {"ENTER", k::Enter},
        {"TAB", k::Tab},
        {"RIGHT", k::Right},
        {"LEFT", k::Left},
        {"DOWN", k::Down},
        {"UP", k::Up},
        {"F1", k::F1},
        {"F2", k::F2},
        {"F3", k::F3},
        {"LEFT_SHIFT", k::LeftShift},
        {"LEFT_CONTROL", k::LeftControl},
        {"LEFT_ALT", k::LeftAlt},
        {"RIGHT_SHIFT", k::RightShift},
        {"RIGHT_CONTROL", k::RightControl},
        {"RIGHT_ALT", k::RightAlt},
    };
    for (const auto& [name, code] : constants) EXPECT_EQ(input::keyFromName(name), code) << name;
}

} // namespace
