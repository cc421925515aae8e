#include "session/setting_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>

namespace session {
namespace {

// Shortest text that reads back as the same float, always with a '.' or exponent so TOML sees a float.
std::string formatFloat(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v));
    std::string s(buf, r.ptr);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
}

std::string formatInt(double v) { return std::to_string(static_cast<long long>(v)); }

// A whole number in [lo, hi]: "" or what is wrong.
std::string parseWhole(std::string_view text, double lo, double hi, std::string_view rangeText, int& out) {
    std::int64_t n = 0;
    const char* end = text.data() + text.size();
    const auto r = std::from_chars(text.data(), end, n);
    if (text.empty() || r.ptr != end || r.ec == std::errc::invalid_argument) return "expected a whole number";
    if (r.ec == std::errc::result_out_of_range || static_cast<double>(n) < lo || static_cast<double>(n) > hi)
        return "out of range " + std::string(rangeText);
    out = static_cast<int>(n);
    return {};
}

} // namespace

const SettingRow* findSetting(std::string_view key) {
    const auto it =
        std::find_if(kSettingRows.begin(), kSettingRows.end(), [&](const SettingRow& r) { return r.key == key; });
    return it == kSettingRows.end() ? nullptr : &*it;
}

std::string settingFloatText(float v) { return formatFloat(v); }

std::string settingText(const SettingRow& row, const Settings& settings) {
    Settings s = settings; // the rows hand out mutable references
    switch (row.type) {
    case SettingType::Int:
        return std::to_string(row.intRef(s));
    case SettingType::Float:
        return formatFloat(row.floatRef(s));
    case SettingType::Bool:
        return row.boolRef(s) ? "true" : "false";
    case SettingType::Size: {
        const PixelSize& size = row.sizeRef(s);
        return std::to_string(size.width) + "x" + std::to_string(size.height);
    }
    }
    return {};
}

std::string settingDefaultText(const SettingRow& row) { return settingText(row, Settings{}); }

std::string settingRangeText(const SettingRow& row) {
    switch (row.type) {
    case SettingType::Int:
        return formatInt(row.lo) + ".." + formatInt(row.hi);
    case SettingType::Float:
        return formatFloat(row.lo) + ".." + formatFloat(row.hi);
    case SettingType::Size:
        return formatInt(row.lo) + ".." + formatInt(row.hi) + " each side";
    case SettingType::Bool:
        return "true or false";
    }
    return {};
}

std::string parseSetting(const SettingRow& row, std::string_view text, Settings& out) {
    const std::string range = settingRangeText(row);
    switch (row.type) {
    case SettingType::Int: {
        int n = 0;
        std::string problem = parseWhole(text, row.lo, row.hi, range, n);
        if (problem.empty()) row.intRef(out) = n;
        return problem;
    }
    case SettingType::Float: {
        double d = 0.0;
        const char* end = text.data() + text.size();
        const auto r = std::from_chars(text.data(), end, d);
        if (text.empty() || r.ptr != end || r.ec == std::errc::invalid_argument) return "expected a number";
        if (std::isnan(d)) return "not a number";
        if (r.ec == std::errc::result_out_of_range || d < row.lo || d > row.hi) return "out of range " + range;
        row.floatRef(out) = static_cast<float>(d);
        return {};
    }
    case SettingType::Bool:
        for (const auto& [yes, no] : {std::pair{"true", "false"}, {"1", "0"}, {"yes", "no"}, {"on", "off"}}) {
            if (text == yes || text == no) {
                row.boolRef(out) = text == yes;
                return {};
            }
        }
        return "expected true or false";
    case SettingType::Size: {
        const std::size_t x = text.find('x');
        if (x == std::string_view::npos) return "expected WIDTHxHEIGHT, e.g. 1280x720";
        PixelSize size;
        for (const auto& [part, side] :
             {std::pair{text.substr(0, x), &size.width}, {text.substr(x + 1), &size.height}}) {
            if (std::string problem = parseWhole(part, row.lo, row.hi, range, *side); !problem.empty())
                return problem == "expected a whole number" ? "expected WIDTHxHEIGHT, e.g. 1280x720" : problem;
        }
        row.sizeRef(out) = size;
        return {};
    }
    }
    return {};
}

void clampSetting(const SettingRow& row, Settings& s) {
    switch (row.type) {
    case SettingType::Int:
        row.intRef(s) = std::clamp(row.intRef(s), static_cast<int>(row.lo), static_cast<int>(row.hi));
        return;
    case SettingType::Float: {
        float& v = row.floatRef(s);
        Settings defaults;
        v = std::isnan(v) ? row.floatRef(defaults)
                          : std::clamp(v, static_cast<float>(row.lo), static_cast<float>(row.hi));
        return;
    }
    case SettingType::Size: {
        PixelSize& size = row.sizeRef(s);
        size.width = std::clamp(size.width, static_cast<int>(row.lo), static_cast<int>(row.hi));
        size.height = std::clamp(size.height, static_cast<int>(row.lo), static_cast<int>(row.hi));
        return;
    }
    case SettingType::Bool:
        return;
    }
}

void clampSettings(Settings& s) {
    for (const SettingRow& row : kSettingRows) clampSetting(row, s);
    holdTriggerRelease(s.input);
}

bool holdTriggerRelease(input::InputConfig& in) {
    if (in.triggerRelease < in.triggerPress) return false;
    const input::InputConfig defaults;
    in.triggerRelease = defaults.triggerRelease < in.triggerPress ? defaults.triggerRelease : in.triggerPress * 0.5f;
    return true;
}

bool sameSetting(const SettingRow& row, const Settings& a, const Settings& b) {
    return settingText(row, a) == settingText(row, b);
}

void copySetting(const SettingRow& row, const Settings& from, Settings& to) {
    // Through the text: settingText writes every type so that parseSetting reads back the same value. Every
    // caller's value is in its range (parsed or clamped), which parseSetting requires.
    parseSetting(row, settingText(row, from), to);
}

} // namespace session
