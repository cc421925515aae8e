#include "session/settings.h"

#include "core/atomic_file.h"
#include "input/action_table.h"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <unistd.h>

namespace session {
namespace {

// One table drives the file's text, the reader and the checks, so a new setting is one line here.
enum class Kind { Int, Float, Bool, Key, Pad };

struct Field {
    std::string_view section, name;
    std::string_view help; // comment lines written above the key; '\n' separates lines
    Kind kind;
    double lo = 0.0, hi = 0.0; // inclusive range for Int and Float
    int& (*intRef)(Settings&) = nullptr;
    float& (*floatRef)(Settings&) = nullptr;
    bool& (*boolRef)(Settings&) = nullptr;
    int input::Bindings::*key = nullptr;                         // Kind::Key
    input::GamepadButton input::GamepadBindings::*pad = nullptr; // Kind::Pad
};

int& keyOf(const Field& f, Settings& s) { return s.input.keys.*f.key; }
input::GamepadButton& padOf(const Field& f, Settings& s) { return s.input.pad.*f.pad; }

Field intField(std::string_view s, std::string_view n, std::string_view h, int lo, int hi, int& (*r)(Settings&)) {
    Field f{s, n, h, Kind::Int, static_cast<double>(lo), static_cast<double>(hi)};
    f.intRef = r;
    return f;
}
Field floatField(std::string_view s, std::string_view n, std::string_view h, double lo, double hi,
                 float& (*r)(Settings&)) {
    Field f{s, n, h, Kind::Float, lo, hi};
    f.floatRef = r;
    return f;
}
Field boolField(std::string_view s, std::string_view n, std::string_view h, bool& (*r)(Settings&)) {
    Field f{s, n, h, Kind::Bool};
    f.boolRef = r;
    return f;
}
constexpr std::string_view kKeysIntro =
    "Keyboard bindings: GLFW key names (\"W\", \"SPACE\", \"LEFT_SHIFT\", \"F2\", \"KP_ADD\"...),\n"
    "or \"none\" to leave an action unbound. Mouse buttons and 1-9 are fixed.";
constexpr std::string_view kPadIntro =
    "Gamepad buttons: a b x y left_bumper right_bumper back start guide left_thumb right_thumb\n"
    "dpad_up dpad_right dpad_down dpad_left, or \"none\". Sticks and triggers are fixed:\n"
    "left stick moves, right stick looks, the triggers step the hotbar.";

// The [keys] and [gamepad] sections: one field per action of input/action_table.h, in its order. The first
// of each section carries the section's explanation (the actions listed first have no comment of their own).
void addBindingFields(std::vector<Field>& table) {
    for (const input::KeyAction& a : input::kKeyActions) {
        Field f{"keys", a.id, table.back().section == "keys" ? a.help : kKeysIntro, Kind::Key};
        f.key = a.key;
        table.push_back(f);
    }
    for (const input::PadAction& a : input::kPadActions) {
        Field f{"gamepad", a.id, table.back().section == "gamepad" ? a.help : kPadIntro, Kind::Pad};
        f.pad = a.button;
        table.push_back(f);
    }
}

// NOLINTNEXTLINE(bugprone-macro-parentheses): a type and a member name cannot be parenthesised
#define MC_REF(type, member) [](Settings& s) -> type& { return s.member; }

std::vector<Field> makeFields() {
    std::vector<Field> table = {
        floatField("graphics", "fov", "Vertical field of view in degrees, 30..120.", 30.0, 120.0, MC_REF(float, fov)),
        intField("graphics", "view_radius", "View distance in chunks, 2..32. Larger costs memory and meshing time.", 2,
                 32, MC_REF(int, viewRadius)),
        intField("graphics", "window_width", "Window size in pixels, 320..16384 each.", 320, 16384,
                 MC_REF(int, windowWidth)),
        intField("graphics", "window_height", "", 320, 16384, MC_REF(int, windowHeight)),
        boolField("graphics", "vsync", "Wait for the display's vertical sync (true/false).", MC_REF(bool, vsync)),
        intField("graphics", "hair_detail",
                 "Hair level of detail: 0 = low (a quarter of each ball's strands), 1 = half, 2 = full.\n"
                 "Fewer strands are simulated and drawn; the balls saved in the world keep their strand count.",
                 0, 2, MC_REF(int, hairDetail)),
        intField("graphics", "hair_budget",
                 "Hair work per tick for all balls together, in thousands of node passes, 100..100000. Past it,\n"
                 "far and unseen balls simulate fewer strands. 1000: 100 balls packed together take about 6 ms\n"
                 "a tick on a 2-core machine (docs/HAIR.md).",
                 static_cast<int>(kMinHairBudgetPasses / 1000), static_cast<int>(kMaxHairBudgetPasses / 1000),
                 MC_REF(int, hairBudgetThousands)),
        intField("simulation", "tick_rate",
                 "Simulation ticks per second, 10..1000. Physics accuracy and cost both grow with it.", 10, 1000,
                 MC_REF(int, tickRate)),
        floatField("mouse", "sensitivity", "Degrees of turn per pixel of mouse motion, 0.001..10.", 0.001, 10.0,
                   MC_REF(float, input.mouseDegreesPerPixel)),
        boolField("mouse", "invert_y", "Moving the mouse (or right stick) up looks down.", MC_REF(bool, input.invertY)),
        floatField("gamepad_tuning", "stick_deadzone",
                   "Radial stick deadzone, 0..0.9 of full deflection; movement starts from 0 at its edge.", 0.0, 0.9,
                   MC_REF(float, input.stickDeadzone)),
        floatField("gamepad_tuning", "look_speed",
                   "Right stick turn speed at full deflection, degrees per second, 1..2000.", 1.0, 2000.0,
                   MC_REF(float, input.lookStickDegreesPerSecond)),
        floatField("gamepad_tuning", "trigger_press",
                   "Trigger travel 0.05..1 at which a pull steps the hotbar; it must then fall below\n"
                   "trigger_release (which must be smaller) before the next pull counts.",
                   // Not 0: no release could be below it, so the trigger would never re-arm (the settings
                   // fuzzer found a file with trigger_press = 0 that warned again after every save).
                   0.05, 1.0, MC_REF(float, input.triggerPress)),
        floatField("gamepad_tuning", "trigger_release", "", 0.0, 1.0, MC_REF(float, input.triggerRelease)),
    };
    addBindingFields(table);
    return table;
}

const std::vector<Field>& fields() {
    static const std::vector<Field> table = makeFields();
    return table;
}

#undef MC_REF

constexpr std::string_view kSections[] = {"graphics", "simulation", "mouse", "gamepad_tuning", "keys", "gamepad"};

// Shortest text that reads back as the same float, always with a '.' or exponent so TOML sees a float.
std::string formatFloat(float v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    std::string s(buf, r.ptr);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
}

std::string quoted(std::string_view s) {
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string out = "\"";
    out += s;
    out += '"';
    return out;
}

// The TOML text of a field's value in these settings.
std::string formatValue(const Field& f, Settings& s) {
    switch (f.kind) {
    case Kind::Int:
        return std::to_string(f.intRef(s));
    case Kind::Float:
        return formatFloat(f.floatRef(s));
    case Kind::Bool:
        return f.boolRef(s) ? "true" : "false";
    case Kind::Key: {
        const std::string_view name = input::keyName(keyOf(f, s));
        return quoted(name.empty() ? "none" : name);
    }
    case Kind::Pad: {
        const std::string_view name = input::gamepadButtonName(padOf(f, s));
        return quoted(name.empty() ? "none" : name);
    }
    }
    return {};
}

std::string defaultText(const Field& f) {
    Settings d;
    return formatValue(f, d);
}

std::string formatRange(const Field& f) {
    std::ostringstream o;
    if (f.kind == Kind::Int) {
        o << static_cast<long long>(f.lo) << ".." << static_cast<long long>(f.hi);
    } else {
        o << formatFloat(static_cast<float>(f.lo)) << ".." << formatFloat(static_cast<float>(f.hi));
    }
    return o.str();
}

// A value as the user wrote it, on one line and short enough for a message.
std::string shortValue(const toml::node& v) {
    if (v.is_table()) return "{...}";
    std::ostringstream o;
    // Strings in double quotes, as the file writes them (toml++ prefers single-quoted literals).
    v.visit([&](const auto& n) { o << toml::toml_formatter(n, toml::format_flags::none); });
    std::string s = o.str();
    std::replace(s.begin(), s.end(), '\n', ' ');
    while (!s.empty() && s.back() == ' ') s.pop_back();
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}

struct Warning {
    std::uint_least32_t line;
    std::string text;
};

struct Conflict {
    const Field* first;
    const Field* second; // nullptr: the first clashes with a fixed key (1-9)
    std::string text;
};

// Bindings that make one press do two things. The mapper has no modes: every action is read on every
// tick, whether walking, flying, paused or with a panel open, so two actions on one key or button
// always fire together (jump and fly up are one action, "jump", and share nothing). Keys 1-9 always
// select a hotbar slot as well.
// A binding as one comparable number (key code, or button index) and its name; -1 when unbound or not a binding.
int bindingCode(const Field& f, Settings& s) {
    if (f.kind == Kind::Key) return keyOf(f, s);
    if (f.kind == Kind::Pad && padOf(f, s) != input::GamepadButton::Count) return static_cast<int>(padOf(f, s));
    return -1;
}
std::string bindingName(const Field& f, int code) {
    return f.kind == Kind::Key
               ? "key " + std::string(input::keyName(code))
               : "gamepad button " + std::string(input::gamepadButtonName(static_cast<input::GamepadButton>(code)));
}

std::vector<Conflict> findConflicts(const Settings& settings) {
    Settings s = settings; // the field table hands out mutable references
    std::vector<Conflict> out;
    const auto& table = fields();
    for (std::size_t i = 0; i < table.size(); ++i) {
        const Field& a = table[i];
        const int code = bindingCode(a, s);
        if (code < 0) continue;
        if (a.kind == Kind::Key && code >= input::key::Digit1 && code <= input::key::Digit9) {
            out.push_back({&a, nullptr,
                           "action '" + std::string(a.name) + "' uses " + bindingName(a, code) +
                               ", which also selects hotbar slot " + std::to_string(code - input::key::Digit1 + 1)});
        }
        for (std::size_t j = i + 1; j < table.size(); ++j) {
            const Field& b = table[j];
            if (b.kind == a.kind && bindingCode(b, s) == code) {
                out.push_back({&a, &b,
                               "actions '" + std::string(a.name) + "' and '" + std::string(b.name) + "' share " +
                                   bindingName(a, code)});
            }
        }
    }
    return out;
}

class SettingsReader {
public:
    SettingsReader(std::string fileName, Settings& settings) : m_file(std::move(fileName)), m_settings(settings) {}

    void read(const toml::table& root) {
        for (const auto& entry : root) {
            // Plain references: clang 14 cannot capture structured bindings in a lambda.
            const std::string section(entry.first.str());
            const toml::node& value = entry.second;
            const bool known =
                std::any_of(fields().begin(), fields().end(), [&](const Field& f) { return f.section == section; });
            if (!known) {
                warn(value,
                     std::string(value.is_table() ? "unknown section '" : "unknown key '") + section + "'; ignored");
                continue;
            }
            if (!value.is_table()) {
                std::string message = "'";
                message += section;
                message += "' = ";
                message += shortValue(value);
                message += ": expected a section [";
                message += section;
                message += "]; its settings keep their defaults";
                warn(value, message);
                continue;
            }
            for (const auto& item : *value.as_table()) {
                const std::string name(item.first.str());
                const toml::node& v = item.second;
                const auto it = std::find_if(fields().begin(), fields().end(),
                                             [&](const Field& f) { return f.section == section && f.name == name; });
                if (it == fields().end()) {
                    std::string message = "unknown key '";
                    message += section;
                    message += '.';
                    message += name;
                    message += "'; ignored";
                    warn(v, message);
                    continue;
                }
                readField(*it, v);
            }
        }
        checkTriggers(root);
        checkConflicts(root);
    }

    std::vector<std::string> warnings() {
        std::stable_sort(m_warnings.begin(), m_warnings.end(),
                         [](const Warning& a, const Warning& b) { return a.line < b.line; });
        std::vector<std::string> out;
        for (auto& w : m_warnings) out.push_back(std::move(w.text));
        return out;
    }

private:
    void warn(const toml::node& at, const std::string& what) {
        const std::uint_least32_t line = at.source().begin.line;
        std::string text = m_file; // piecewise: GCC 12 warns falsely (-Wrestrict) on ":" + std::to_string(...)
        if (line > 0) text += ':', text += std::to_string(line);
        text += ": ";
        text += what;
        m_warnings.push_back({line, std::move(text)});
    }

    void bad(const Field& f, const toml::node& v, const std::string& what, const std::string& using_) {
        warn(v, "key '" + std::string(f.section) + "." + std::string(f.name) + "' = " + shortValue(v) + ": " + what +
                    "; using " + using_);
    }

    void readField(const Field& f, const toml::node& v) {
        const std::string def = defaultText(f);
        switch (f.kind) {
        case Kind::Int: {
            if (!v.is_integer()) return bad(f, v, "expected a whole number", def);
            const std::int64_t n = v.as_integer()->get();
            if (n < f.lo || n > f.hi) return bad(f, v, "out of range " + formatRange(f), def);
            f.intRef(m_settings) = static_cast<int>(n);
            return;
        }
        case Kind::Float: {
            double d;
            if (v.is_floating_point()) {
                d = v.as_floating_point()->get();
            } else if (v.is_integer()) {
                d = static_cast<double>(v.as_integer()->get());
            } else {
                return bad(f, v, "expected a number", def);
            }
            if (std::isnan(d)) return bad(f, v, "not a number", def);
            if (d < f.lo || d > f.hi) return bad(f, v, "out of range " + formatRange(f), def);
            f.floatRef(m_settings) = static_cast<float>(d);
            return;
        }
        case Kind::Bool:
            if (!v.is_boolean()) return bad(f, v, "expected true or false", def);
            f.boolRef(m_settings) = v.as_boolean()->get();
            return;
        case Kind::Key: {
            if (!v.is_string()) return bad(f, v, "expected a key name in quotes, e.g. \"W\"", def);
            const std::string& name = v.as_string()->get();
            if (name == "none") {
                keyOf(f, m_settings) = -1;
                return;
            }
            const auto key = input::keyFromName(name);
            if (!key) return bad(f, v, "unknown key name (GLFW names, e.g. \"SPACE\", \"LEFT_SHIFT\")", def);
            keyOf(f, m_settings) = *key;
            return;
        }
        case Kind::Pad: {
            if (!v.is_string()) return bad(f, v, "expected a button name in quotes, e.g. \"a\"", def);
            const std::string& name = v.as_string()->get();
            if (name == "none") {
                padOf(f, m_settings) = input::GamepadButton::Count;
                return;
            }
            const auto button = input::gamepadButtonFromName(name);
            if (!button) return bad(f, v, "unknown button name (a, b, left_bumper, dpad_up...)", def);
            padOf(f, m_settings) = *button;
            return;
        }
        }
    }

    // Each threshold may be valid alone while the pair is not: a release at or above the press would
    // let a trigger resting between them fire every tick.
    void checkTriggers(const toml::table& root) {
        input::InputConfig& c = m_settings.input;
        if (c.triggerRelease < c.triggerPress) return;
        const input::InputConfig d;
        const float fallback = d.triggerRelease < c.triggerPress ? d.triggerRelease : c.triggerPress * 0.5f;
        const Field* release = nullptr;
        for (const Field& f : fields())
            if (f.section == "gamepad_tuning" && f.name == "trigger_release") release = &f;
        // Point at whichever of the two the user wrote (release first): that is the line to fix.
        const toml::node* at = nullptr;
        for (const char* name : {"trigger_release", "trigger_press"}) {
            if (at) break;
            if (const toml::table* tuning = root["gamepad_tuning"].as_table()) at = tuning->get(name);
        }
        const std::string what = "must be below trigger_press (" + formatFloat(c.triggerPress) + ")";
        if (at) {
            bad(*release, *at, what, formatFloat(fallback));
        } else {
            m_warnings.push_back(
                {0, m_file + ": key 'gamepad_tuning.trigger_release': " + what + "; using " + formatFloat(fallback)});
        }
        c.triggerRelease = fallback;
    }

    // Points at the later of the two lines the user wrote: the binding most likely just changed.
    void checkConflicts(const toml::table& root) {
        const auto written = [&](const Field* f) -> const toml::node* {
            if (!f) return nullptr;
            const toml::table* section = root[f->section].as_table();
            return section ? section->get(f->name) : nullptr;
        };
        for (const Conflict& c : findConflicts(m_settings)) {
            const toml::node* at = nullptr;
            for (const Field* f : {c.first, c.second}) {
                const toml::node* v = written(f);
                if (v && (!at || v->source().begin.line > at->source().begin.line)) at = v;
            }
            const std::string text = c.text + "; one press does both";
            if (at) {
                warn(*at, text);
            } else {
                m_warnings.push_back({0, m_file + ": " + text});
            }
        }
    }

    std::string m_file;
    Settings& m_settings;
    std::vector<Warning> m_warnings;
};

} // namespace

std::vector<std::string> bindingConflicts(const Settings& settings) {
    std::vector<std::string> out;
    for (Conflict& c : findConflicts(settings)) out.push_back(std::move(c.text));
    return out;
}

std::int64_t hairBudgetPasses(const Settings& s) { return std::int64_t{1000} * s.hairBudgetThousands; }

float hairDetailFraction(int hairDetail) { return hairDetail <= 0 ? 0.25f : hairDetail == 1 ? 0.5f : 1.0f; }

std::string settingsText(const Settings& settings) {
    Settings s = settings; // the field table hands out mutable references
    std::ostringstream o;
    o << "# Minecrappy settings. The game reads this file at start and the settings panel (pause menu)\n"
         "# rewrites it when you press Save, so comments you add here are not kept.\n"
         "# A bad value is reported with its line and replaced by its default; a missing key takes its\n"
         "# default. Delete the file to get the defaults back. The flags --size, --fov, --view-radius,\n"
         "# --tick-rate and --vsync override this file for one run.\n";
    for (const std::string_view section : kSections) {
        o << "\n[" << section << "]\n";
        for (const Field& f : fields()) {
            if (f.section != section) continue;
            if (!f.help.empty()) {
                std::string_view help = f.help;
                while (!help.empty()) {
                    const auto nl = help.find('\n');
                    o << "# " << help.substr(0, nl) << "\n";
                    help = nl == std::string_view::npos ? std::string_view() : help.substr(nl + 1);
                }
            }
            o << f.name << " = " << formatValue(f, s);
            const std::string def = defaultText(f);
            if (formatValue(f, s) != def) o << "  # default " << def;
            o << "\n";
        }
    }
    return o.str();
}

std::string defaultSettingsText() { return settingsText(Settings{}); }

void saveSettings(const Settings& settings, const std::filesystem::path& file) {
    const auto fail = [&](const std::string& why) {
        std::string message = "cannot write settings file "; // piecewise: GCC 12's false -Wrestrict on literal + &&
        message += file.string();
        message += ": ";
        message += why;
        throw std::runtime_error(message);
    };
    std::error_code ec;
    if (file.has_parent_path()) {
        std::filesystem::create_directories(file.parent_path(), ec);
        if (ec) fail(ec.message());
    }
    try {
        core::AtomicFile out(file);
        out.stream() << settingsText(settings);
        out.commit();
    } catch (const std::runtime_error& e) {
        fail(e.what());
    }
}

SettingsLoad loadSettings(const std::filesystem::path& file) {
    SettingsLoad out;
    const std::string name = file.string();
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (status.type() == std::filesystem::file_type::not_found) {
        try {
            saveSettings(out.settings, file);
            out.created = true;
        } catch (const std::exception& e) {
            out.warnings.push_back(std::string(e.what()) + "; using built-in defaults");
        }
        return out;
    }
    // Only regular files: a directory or a device has no size to read, and a FIFO could block for ever.
    if (status.type() != std::filesystem::file_type::regular) {
        out.warnings.push_back(name + ": not a regular file, using built-in defaults");
        return out;
    }
    std::ifstream in(file, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.is_open() || in.bad()) {
        out.warnings.push_back(name + ": cannot be read, using built-in defaults");
        return out;
    }
    return parseSettings(text, name);
}

SettingsLoad parseSettings(std::string_view text, const std::string& name) {
    SettingsLoad out;
    toml::table root;
    try {
        root = toml::parse(text, name);
    } catch (const toml::parse_error& e) {
        std::ostringstream what;
        what << name << ":" << e.source().begin.line << ":" << e.source().begin.column << ": " << e.description();
        out.warnings.push_back(
            name + ": not a valid settings file, using built-in defaults (the file is left as it is):\n" + what.str());
        return out;
    }
    SettingsReader reader(name, out.settings);
    try {
        reader.read(root);
    } catch (const std::exception& e) {
        // Not expected (every access is type-checked first), but a settings file must never stop the game.
        out.settings = Settings{};
        out.warnings = reader.warnings();
        out.warnings.push_back(name + ": " + e.what() + "; using built-in defaults");
        return out;
    }
    out.warnings = reader.warnings();
    return out;
}

} // namespace session
