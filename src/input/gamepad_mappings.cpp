#include "input/gamepad_mappings.h"

#include "core/quote.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <initializer_list>

namespace input {

namespace {

// The elements SDL's format defines; GLFW uses the first 21 and ignores the rest.
constexpr std::array<std::string_view, 30> kElements{
    "a",
    "b",
    "x",
    "y",
    "back",
    "guide",
    "start",
    "leftstick",
    "rightstick",
    "leftshoulder",
    "rightshoulder",
    "dpup",
    "dpdown",
    "dpleft",
    "dpright",
    "leftx",
    "lefty",
    "rightx",
    "righty",
    "lefttrigger",
    "righttrigger",
    "misc1",
    "paddle1",
    "paddle2",
    "paddle3",
    "paddle4",
    "touchpad",
    "crc",
    "hint",
    "sdk>=",
};

// Joins pieces (GCC 12 warns falsely, -Wrestrict, on "literal" + std::string temporaries).
std::string cat(std::initializer_list<std::string_view> parts) {
    std::string out;
    for (const std::string_view p : parts) out += p;
    return out;
}

bool digits(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// bN, aN with optional +/- before and ~ after, hN.M.
bool validSource(std::string_view s) {
    if (!s.empty() && (s.front() == '+' || s.front() == '-')) s.remove_prefix(1);
    if (!s.empty() && s.back() == '~') s.remove_suffix(1);
    if (s.size() < 2) return false;
    const char kind = s.front();
    const std::string_view rest = s.substr(1);
    if (kind == 'b' || kind == 'a') return digits(rest);
    if (kind == 'h') {
        const std::size_t dot = rest.find('.');
        return dot != std::string_view::npos && digits(rest.substr(0, dot)) && digits(rest.substr(dot + 1));
    }
    return false;
}

// Empty when the line is a good mapping, else what is wrong with it.
std::string problemWith(std::string_view line) {
    const std::vector<std::string_view> fields = core::splitAt(line, ',');
    if (fields.size() < 3) return "expected GUID,NAME,ELEMENT:SOURCE,...";
    const std::string_view guid = fields[0];
    if (guid.size() != 32 ||
        !std::all_of(guid.begin(), guid.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); }))
        return cat({"the GUID '", guid, "' is not 32 hexadecimal digits"});
    if (fields[1].empty()) return "the name is empty";
    bool any = false;
    for (std::size_t i = 2; i < fields.size(); ++i) {
        const std::string_view f = fields[i];
        if (f.empty()) continue; // the format ends lines with a comma
        const std::size_t colon = f.find(':');
        if (colon == std::string_view::npos) return cat({"'", f, "' is not ELEMENT:SOURCE"});
        const std::string_view element = f.substr(0, colon), source = f.substr(colon + 1);
        if (element == "platform") continue;
        std::string_view name = element;
        if (!name.empty() && (name.front() == '+' || name.front() == '-')) name.remove_prefix(1);
        if (std::find(kElements.begin(), kElements.end(), name) == kElements.end())
            return cat({"unknown element '", element, "'"});
        if (name == "crc" || name == "hint" || name == "sdk>=") continue;
        if (!validSource(source)) return cat({"'", source, "' for ", element, " is not bN, aN or hN.M"});
        any = true;
    }
    if (!any) return "the mapping maps no button or axis";
    return {};
}

} // namespace

GamepadMappings parseGamepadMappings(std::string_view text, std::string_view fileName) {
    GamepadMappings out;
    int number = 0;
    for (std::string_view line : core::splitAt(text, '\n')) {
        ++number;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
            line.remove_suffix(1);
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
        if (line.empty() || line.front() == '#') continue;
        if (const std::string why = problemWith(line); !why.empty()) {
            out.problems.push_back(cat({fileName, ":", std::to_string(number), ": ", why}));
        } else {
            out.lines.emplace_back(line);
        }
    }
    return out;
}

std::string padLabel(bool connected, bool mapped, std::string_view name) {
    if (!connected) return {};
    if (name.empty()) name = mapped ? "gamepad" : "joystick";
    return cat({name, mapped ? " (mapped)" : " (no mapping)"});
}

} // namespace input
