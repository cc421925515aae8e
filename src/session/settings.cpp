#include "session/settings.h"

#include "core/atomic_file.h"
#include "input/action_table.h"
#include "session/setting_table.h"

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

// The file's keys: a row of session/setting_table.h each, then one per binding of input/action_table.h.
enum class Kind { Setting, Key, Pad };

struct Field {
    std::string_view section, name;
    std::string_view help; // comment lines written above the key; '\n' separates lines
    Kind kind;
    const SettingRow* row = nullptr;                             // Kind::Setting
    int input::Bindings::*key = nullptr;                         // Kind::Key
    input::GamepadButton input::GamepadBindings::*pad = nullptr; // Kind::Pad
};

int& keyOf(const Field& f, Settings& s) { return s.input.keys.*f.key; }
input::GamepadButton& padOf(const Field& f, Settings& s) { return s.input.pad.*f.pad; }

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

std::vector<Field> makeFields() {
    std::vector<Field> table;
    table.reserve(kSettingRows.size() + input::kKeyActions.size() + input::kPadActions.size());
    for (const SettingRow& row : kSettingRows) table.push_back({row.section, row.key, row.help, Kind::Setting, &row});
    addBindingFields(table);
    return table;
}

const std::vector<Field>& fields() {
    static const std::vector<Field> table = makeFields();
    return table;
}

constexpr std::array<std::string_view, kSettingSections.size() + 2> kSections = [] {
    std::array<std::string_view, kSettingSections.size() + 2> all{};
    for (std::size_t i = 0; i < kSettingSections.size(); ++i) all[i] = kSettingSections[i];
    all[kSettingSections.size()] = "keys";
    all[kSettingSections.size() + 1] = "gamepad";
    return all;
}();

std::string inQuotes(std::string_view s) {
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string out = "\"";
    out += s;
    out += '"';
    return out;
}

// The TOML text of a field's value in these settings.
std::string formatValue(const Field& f, Settings& s) {
    switch (f.kind) {
    case Kind::Setting: {
        const std::string text = settingText(*f.row, s);
        return f.row->type == SettingType::Size ? inQuotes(text) : text;
    }
    case Kind::Key: {
        const std::string_view name = input::keyName(keyOf(f, s));
        return inQuotes(name.empty() ? "none" : name);
    }
    case Kind::Pad: {
        const std::string_view name = input::gamepadButtonName(padOf(f, s));
        return inQuotes(name.empty() ? "none" : name);
    }
    }
    return {};
}

std::string defaultText(const Field& f) {
    Settings d;
    return formatValue(f, d);
}

// The comment line after a setting's help: its range and unit ("30.0..120.0, degrees"); "" for a Bool row.
std::string rangeComment(const SettingRow& row) {
    if (row.type == SettingType::Bool) return {};
    std::string text = settingRangeText(row);
    if (!row.unit.empty()) text += ", " + std::string(row.unit);
    if (!row.choices.empty()) {
        std::string names(row.choices);
        std::replace(names.begin(), names.end(), '|', ',');
        text += " (" + names + ")";
    }
    if (!row.live) text += "; applies from the next start";
    return text;
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
                if (it == fields().end() && readRenamed(*value.as_table(), section, name, v)) continue;
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

    std::vector<std::string> warnings() { return byLine(m_warnings); }
    std::vector<std::string> notes() { return byLine(m_notes); }
    bool migrated() const { return m_migrated; }

private:
    static std::vector<std::string> byLine(std::vector<Warning>& lines) {
        std::stable_sort(lines.begin(), lines.end(),
                         [](const Warning& a, const Warning& b) { return a.line < b.line; });
        std::vector<std::string> out;
        out.reserve(lines.size());
        for (auto& w : lines) out.push_back(w.text);
        return out;
    }

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
        case Kind::Setting:
            return readSetting(f, v, def);
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

    // A setting's value: the TOML type its row asks for, then the row's own check (session/setting_table.h).
    void readSetting(const Field& f, const toml::node& v, const std::string& def) {
        const SettingRow& row = *f.row;
        std::string text;
        switch (row.type) {
        case SettingType::Int:
            if (!v.is_integer()) return bad(f, v, "expected a whole number", def);
            text = std::to_string(v.as_integer()->get());
            break;
        case SettingType::Float: {
            if (!v.is_floating_point() && !v.is_integer()) return bad(f, v, "expected a number", def);
            const double d = v.is_integer() ? static_cast<double>(v.as_integer()->get()) : v.as_floating_point()->get();
            if (std::isnan(d)) return bad(f, v, "not a number", def);
            char buf[64];
            text.assign(buf, std::to_chars(buf, buf + sizeof buf, d).ptr);
            break;
        }
        case SettingType::Bool:
            if (!v.is_boolean()) return bad(f, v, "expected true or false", def);
            text = v.as_boolean()->get() ? "true" : "false";
            break;
        case SettingType::Size:
            if (!v.is_string()) return bad(f, v, "expected \"WIDTHxHEIGHT\" in quotes, e.g. \"1280x720\"", def);
            text = v.as_string()->get();
            break;
        }
        if (std::string problem = parseSetting(row, text, m_settings); !problem.empty()) bad(f, v, problem, def);
    }

    // A key an older build wrote for a setting that has a new name: read into the new one, with a note. A Size's
    // two old keys each carry one side. Written beside the new key, the old one is ignored with a warning naming
    // both lines (the new key wins, whichever comes first; the warning keeps the file from being rewritten).
    bool readRenamed(const toml::table& table, std::string_view section, std::string_view name, const toml::node& v) {
        for (const SettingRow& row : kSettingRows) {
            if (row.section != section) continue;
            for (std::size_t side = 0; side < row.renamedFrom.size(); ++side) {
                if (row.renamedFrom[side].empty() || row.renamedFrom[side] != name) continue;
                const std::string old = std::string(section) + "." + std::string(name);
                const std::string now = std::string(section) + "." + std::string(row.key);
                if (const toml::node* newer = table.get(row.key)) {
                    std::string text = "key '";
                    for (const std::string& part :
                         {old, std::string("' is the old name of '"), now, std::string("', which line "),
                          std::to_string(newer->source().begin.line), std::string(" sets; '"), now,
                          std::string("' wins, '"), old, std::string("' ignored")})
                        text += part;
                    warn(v, text);
                    return true;
                }
                if (row.type != SettingType::Size) {
                    readSetting(Field{section, name, {}, Kind::Setting, &row}, v, settingDefaultText(row));
                } else if (!v.is_integer() || v.as_integer()->get() < row.lo || v.as_integer()->get() > row.hi) {
                    const PixelSize d;
                    warn(v, "key '" + old + "' = " + shortValue(v) + ": expected a whole number in " +
                                settingRangeText(row) + "; using " + std::to_string(side == 0 ? d.width : d.height));
                    return true;
                } else {
                    PixelSize& size = row.sizeRef(m_settings);
                    (side == 0 ? size.width : size.height) = static_cast<int>(v.as_integer()->get());
                }
                std::string note = m_file;
                note += ':';
                note += std::to_string(v.source().begin.line);
                for (const std::string_view part :
                     {std::string_view(": key '"), std::string_view(old), std::string_view("' is now '"),
                      std::string_view(now), std::string_view("'; read as such")})
                    note += part;
                m_notes.push_back({v.source().begin.line, std::move(note)});
                m_migrated = true;
                return true;
            }
        }
        return false;
    }

    // Each threshold may be valid alone while the pair is not: a release at or above the press would
    // let a trigger resting between them fire every tick.
    void checkTriggers(const toml::table& root) {
        input::InputConfig& c = m_settings.input;
        const float press = c.triggerPress;
        if (!holdTriggerRelease(c)) return;
        const Field* release = nullptr;
        for (const Field& f : fields())
            if (f.section == "gamepad_tuning" && f.name == "trigger_release") release = &f;
        // Point at whichever of the two the user wrote (release first): that is the line to fix.
        const toml::node* at = nullptr;
        for (const char* name : {"trigger_release", "trigger_press"}) {
            if (at) break;
            if (const toml::table* tuning = root["gamepad_tuning"].as_table()) at = tuning->get(name);
        }
        const std::string what = "must be below trigger_press (" + settingFloatText(press) + ")";
        if (at) {
            bad(*release, *at, what, settingFloatText(c.triggerRelease));
        } else {
            m_warnings.push_back({0, m_file + ": key 'gamepad_tuning.trigger_release': " + what + "; using " +
                                         settingFloatText(c.triggerRelease)});
        }
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
    std::vector<Warning> m_warnings, m_notes;
    bool m_migrated = false;
};

} // namespace

std::vector<std::string> bindingConflicts(const Settings& settings) {
    std::vector<std::string> out;
    for (Conflict& c : findConflicts(settings)) out.push_back(std::move(c.text));
    return out;
}

std::int64_t hairBudgetPasses(const Settings& s) { return std::int64_t{1000} * s.hairBudgetThousands; }

float hairDetailFraction(int hairDetail) { return hairDetail <= 0 ? 0.25f : hairDetail == 1 ? 0.5f : 1.0f; }

namespace {

// The flags that override the file for one run, "--fov, --view-radius, ... and --tick-rate".
std::string overridingFlags() {
    std::vector<std::string_view> flags;
    for (const SettingRow& row : kSettingRows)
        if (!row.flag.empty()) flags.push_back(row.flag);
    std::string text;
    for (std::size_t i = 0; i < flags.size(); ++i) {
        if (i > 0) text += i + 1 == flags.size() ? " and " : ", ";
        text += flags[i];
    }
    return text;
}

void writeComment(std::ostream& o, std::string_view text) {
    while (!text.empty()) {
        const auto nl = text.find('\n');
        o << "# " << text.substr(0, nl) << "\n";
        text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
    }
}

} // namespace

std::string settingsText(const Settings& settings) {
    Settings s = settings; // the field table hands out mutable references
    std::ostringstream o;
    o << "# Minecrappy settings. The game reads this file at start and the settings panel (pause menu)\n"
         "# rewrites it when you press Save, so comments you add here are not kept.\n"
         "# A bad value is reported with its line and replaced by its default; a missing key takes its\n"
         "# default. Delete the file to get the defaults back. The flags\n";
    writeComment(o, overridingFlags() + " override this file for one run.");
    for (const std::string_view section : kSections) {
        o << "\n[" << section << "]\n";
        for (const Field& f : fields()) {
            if (f.section != section) continue;
            writeComment(o, f.help);
            if (f.row) writeComment(o, rangeComment(*f.row));
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
    out = parseSettings(text, name);
    // Keys renamed since the file was written: the file is rewritten under the new names, the old text kept beside
    // it. Only a file that read without a problem: one with a bad value keeps the user's text to fix.
    if (out.migrated && out.warnings.empty()) {
        // A free name: an earlier backup (or the player's own file of that name) is never replaced.
        std::filesystem::path old = name + ".old";
        for (int n = 1; std::filesystem::exists(old, ec); ++n) old = name + ".old." + std::to_string(n);
        try {
            core::writeOutput(old, text);
            saveSettings(out.settings, file);
            out.notes.push_back(name + ": rewritten with the new key names; the old file is " + old.string());
        } catch (const std::exception& e) {
            out.warnings.push_back(std::string(e.what()) + "; the file keeps its old key names, which are still read");
        }
    }
    return out;
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
    out.notes = reader.notes();
    out.migrated = reader.migrated();
    return out;
}

} // namespace session
