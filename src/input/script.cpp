#include "input/script.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <system_error>

#include "core/quote.h"
#include "input/keys.h"

namespace input {
namespace {

std::string quote(std::string_view token) { return core::quoteForMessage(token); }

struct Command {
    std::string_view name;
    std::string_view usage;
    std::size_t argCount; // exactly this many; with `variadic`, at least this many
    bool variadic = false;
};

constexpr std::array kCommands{
    Command{"key", "NAME down|up", 2},
    Command{"mouse_move", "DX DY", 2},
    Command{"mouse_button", "left|right|middle down|up", 2},
    Command{"scroll", "DY", 1},
    Command{"gamepad_axis", "NAME VALUE", 2},
    Command{"gamepad_button", "NAME down|up", 2},
    Command{"teleport", "X Y Z", 3},
    Command{"look", "YAW PITCH", 2},
    Command{"act", "[move=X,Y] [yaw=D] [pitch=D] [select=N] [slot=N] [teleport=X,Y,Z] [look=YAW,PITCH] [FLAG...]", 0,
            true},
    Command{"pendulum", "INDEX set|release|reset [FIELD=VALUE...]", 2, true},
    Command{"hair", "INDEX FIELD=VALUE...", 1, true},
    Command{"time", "HOURS", 1},
    Command{"hotbar", "SLOT ITEM", 2},
};

constexpr std::string_view kCommandList =
    "key, mouse_move, mouse_button, scroll, gamepad_axis, gamepad_button, teleport, look, act, pendulum, hair, time, "
    "hotbar";

// The flags of an `act` line, each an Actions field that is true for the tick.
struct ActFlag {
    std::string_view name;
    bool Actions::*field;
};
constexpr std::array kActFlags{
    ActFlag{"jump", &Actions::jump},
    ActFlag{"descend", &Actions::descend},
    ActFlag{"sprint", &Actions::sprint},
    ActFlag{"place", &Actions::place},
    ActFlag{"break", &Actions::breakBlock},
    ActFlag{"pick", &Actions::pickBlock},
    ActFlag{"interact", &Actions::interact},
    ActFlag{"carry", &Actions::carry},
    ActFlag{"fly", &Actions::toggleFly},
    ActFlag{"pause", &Actions::togglePause},
    ActFlag{"screenshot", &Actions::screenshot},
    ActFlag{"overlay", &Actions::toggleOverlay},
    ActFlag{"help", &Actions::toggleHelp},
};

// The shortest text that reads back as exactly this float.
std::string exactFloat(float v) { return core::shortestText(v); }

struct ValueRange {
    double lo;
    double hi;
    std::string_view text; // how the range reads in a message
};

constexpr double kFloatMax = std::numeric_limits<float>::max();
constexpr ValueRange kAnyFloat{-kFloatMax, kFloatMax, "the float range"};
constexpr ValueRange kUnit{-1.0, 1.0, "-1..1"};
constexpr ValueRange kPitch{-90.0, 90.0, "-90..90"};
// Trigger thresholds (mapper.h) are on 0..1 travel, so scripts write triggers the same way.
constexpr ValueRange kTriggerTravel{0.0, 1.0, "0..1 (trigger travel: 0 released, 1 fully pulled)"};

bool isSeparator(char c) {
    // '\r' counts as a separator so CRLF files parse like LF files.
    return c == ' ' || c == '\t' || c == '\r';
}

void tokenize(std::string_view line, std::vector<std::string_view>& tokens) {
    tokens.clear();
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isSeparator(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !isSeparator(line[i])) ++i;
        if (i > start) tokens.push_back(line.substr(start, i - start));
    }
}

// Parses one tokenized line. Each check fails with a message a person can act on without reading
// this file: what was expected, and the token that was found.
class LineParser {
public:
    LineParser(std::string_view fileName, int line, const std::vector<std::string_view>& tokens)
        : m_fileName(fileName), m_line(line), m_tokens(tokens) {}

    ScriptEvent parse() const {
        const std::uint64_t tick = parseTick(m_tokens[0]);
        if (m_tokens.size() < 2)
            fail("missing command after tick " + quote(m_tokens[0]) + " (expected one of " + std::string(kCommandList) +
                 ")");
        const std::string_view name = m_tokens[1];
        const auto command =
            std::find_if(kCommands.begin(), kCommands.end(), [&](const Command& c) { return c.name == name; });
        if (command == kCommands.end())
            fail("unknown command " + quote(name) + " (expected one of " + std::string(kCommandList) + ")");
        checkArgCount(*command);
        if (name == "pendulum" || name == "hair") {
            EditEvent edit{std::string(name), parseIndex(arg(0)), {}};
            for (std::size_t i = 3; i < m_tokens.size(); ++i) edit.words.emplace_back(m_tokens[i]);
            return ScriptEvent{tick, m_line, InputEvent{}, std::move(edit)};
        }
        if (name == "time") return ScriptEvent{tick, m_line, InputEvent{}, EditEvent{"time", 0, {std::string(arg(0))}}};
        if (name == "hotbar") {
            return ScriptEvent{tick, m_line, InputEvent{},
                               EditEvent{"hotbar", parseIndex(arg(0)), {std::string(arg(1))}}};
        }
        return ScriptEvent{tick, m_line, parseEvent(name), std::nullopt};
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw ScriptError(std::string(m_fileName) + ":" + std::to_string(m_line) + ": " + what);
    }

    std::string_view arg(std::size_t i) const { return m_tokens[2 + i]; }

    void checkArgCount(const Command& command) const {
        const std::size_t got = m_tokens.size() - 2;
        const std::string usage = std::string(command.name) + " " + std::string(command.usage);
        if (got < command.argCount) {
            // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
            std::string message = "'";
            message += command.name;
            message +=
                "' needs " + std::to_string(command.argCount) + (command.argCount == 1 ? " argument" : " arguments");
            message += " (" + usage + "), got " + std::to_string(got);
            fail(message);
        }
        if (got > command.argCount && !command.variadic)
            fail("unexpected extra token " + quote(m_tokens[2 + command.argCount]) + " (" + usage + ")");
    }

    InputEvent parseEvent(std::string_view command) const {
        if (command == "key") return KeyEvent{parseKey(arg(0)), parseDownUp(arg(1))};
        if (command == "mouse_move")
            return MouseMoveEvent{parseNumber(arg(0), "DX", kAnyFloat), parseNumber(arg(1), "DY", kAnyFloat)};
        if (command == "mouse_button") return MouseButtonEvent{parseMouseButton(arg(0)), parseDownUp(arg(1))};
        if (command == "scroll") return ScrollEvent{parseNumber(arg(0), "DY", kAnyFloat)};
        if (command == "gamepad_axis") return parseAxisEvent();
        if (command == "gamepad_button") return GamepadButtonEvent{parseButton(arg(0)), parseDownUp(arg(1))};
        if (command == "teleport")
            return TeleportEvent{{parseNumber(arg(0), "X", kAnyFloat), parseNumber(arg(1), "Y", kAnyFloat),
                                  parseNumber(arg(2), "Z", kAnyFloat)}};
        if (command == "look")
            return LookEvent{parseNumber(arg(0), "YAW", kAnyFloat), parseNumber(arg(1), "PITCH", kPitch)};
        return ActionsEvent{parseActions()};
    }

    std::uint64_t parseIndex(std::string_view token) const {
        std::uint64_t index = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
        if (ec != std::errc{} || end != token.data() + token.size())
            fail("bad index " + quote(token) + " (expected a non-negative integer: which object, in placing order)");
        return index;
    }

    // Floats exactly as written (a recording writes the shortest text that reads back bit for bit).
    std::vector<float> parseFloats(std::string_view key, std::string_view text, std::size_t count) const {
        const std::vector<std::string_view> parts = core::splitAt(text, ',');
        if (parts.size() != count)
            fail("act " + std::string(key) + " needs " + std::to_string(count) + " numbers separated by commas, got " +
                 quote(text));
        std::vector<float> out;
        for (const std::string_view part : parts) {
            float v = 0.0f;
            const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
            if (ec != std::errc{} || end != part.data() + part.size() || !std::isfinite(v))
                fail("act " + std::string(key) + ": " + quote(part) + " is not a finite number");
            out.push_back(v);
        }
        return out;
    }

    int parseInt(std::string_view key, std::string_view text, int lo, int hi) const {
        int v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc{} || end != text.data() + text.size() || v < lo || v > hi)
            fail("act " + std::string(key) + ": " + quote(text) + " is not an integer in " + std::to_string(lo) + ".." +
                 std::to_string(hi));
        return v;
    }

    Actions parseActions() const {
        Actions a;
        for (std::size_t i = 2; i < m_tokens.size(); ++i) {
            const std::string_view token = m_tokens[i];
            const std::size_t eq = token.find('=');
            const std::string_view key = token.substr(0, eq);
            const std::string_view value = eq == std::string_view::npos ? std::string_view() : token.substr(eq + 1);
            if (eq == std::string_view::npos) {
                const auto flag =
                    std::find_if(kActFlags.begin(), kActFlags.end(), [&](const ActFlag& f) { return f.name == token; });
                if (flag == kActFlags.end())
                    fail("act: unknown flag " + quote(token) +
                         " (expected jump, descend, sprint, place, break, pick, interact, carry, fly, pause, "
                         "screenshot, overlay, help, or FIELD=VALUE)");
                a.*flag->field = true;
            } else if (key == "move") {
                const auto v = parseFloats(key, value, 2);
                if (v[0] * v[0] + v[1] * v[1] > 1.0001f) fail("act move: " + quote(value) + " is longer than 1");
                a.move = {v[0], v[1]};
            } else if (key == "yaw") {
                a.yawDelta = parseFloats(key, value, 1)[0];
            } else if (key == "pitch") {
                a.pitchDelta = parseFloats(key, value, 1)[0];
            } else if (key == "select") {
                a.selectDelta = parseInt(key, value, -1000000, 1000000);
            } else if (key == "slot") {
                a.selectSlot = parseInt(key, value, 0, 8);
            } else if (key == "teleport") {
                const auto v = parseFloats(key, value, 3);
                a.teleport = glm::vec3(v[0], v[1], v[2]);
            } else if (key == "look") {
                const auto v = parseFloats(key, value, 2);
                if (v[1] < -90.0f || v[1] > 90.0f) fail("act look: pitch " + exactFloat(v[1]) + " is outside -90..90");
                a.lookAbsolute = glm::vec2(v[0], v[1]);
            } else {
                fail("act: unknown field " + quote(key) +
                     " (expected move, yaw, pitch, select, slot, teleport or look)");
            }
        }
        return a;
    }

    GamepadAxisEvent parseAxisEvent() const {
        const GamepadAxis axis = parseAxis(arg(0));
        if (axis == GamepadAxis::LeftTrigger || axis == GamepadAxis::RightTrigger) {
            // GLFW reports a released trigger as -1; the event carries what a real pad would.
            return GamepadAxisEvent{axis, 2.0f * parseNumber(arg(1), "VALUE", kTriggerTravel) - 1.0f};
        }
        return GamepadAxisEvent{axis, parseNumber(arg(1), "VALUE", kUnit)};
    }

    std::uint64_t parseTick(std::string_view token) const {
        std::uint64_t tick = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), tick);
        if (ec == std::errc::result_out_of_range ||
            (ec == std::errc{} && end == token.data() + token.size() && tick > kMaxScriptTick))
            fail("tick " + quote(token) + " is beyond 2^53 (9007199254740992)");
        if (ec != std::errc{} || end != token.data() + token.size())
            fail("bad tick " + quote(token) + " (expected a non-negative integer at the start of the line)");
        return tick;
    }

    float parseNumber(std::string_view token, std::string_view what, const ValueRange& range) const {
        double value = 0.0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        const std::string label = std::string(m_tokens[1]) + " " + std::string(what) + " " + quote(token);
        if (ec == std::errc::result_out_of_range) fail(label + " is out of range");
        // from_chars accepts "nan" and "inf"; neither means anything as an input value.
        if (ec != std::errc{} || end != token.data() + token.size() || !std::isfinite(value))
            fail(label + " is not a number (expected e.g. 3, -0.5 or 1e2)");
        if (value < range.lo || value > range.hi) fail(label + " is outside " + std::string(range.text));
        return static_cast<float>(value);
    }

    bool parseDownUp(std::string_view token) const {
        if (token == "down") return true;
        if (token == "up") return false;
        fail("expected down or up, got " + quote(token));
    }

    int parseKey(std::string_view token) const {
        if (const auto key = keyFromName(token)) return *key;
        constexpr std::string_view kPrefix = "GLFW_KEY_";
        if (token.substr(0, kPrefix.size()) == kPrefix && keyFromName(token.substr(kPrefix.size())))
            fail("unknown key " + quote(token) + " (drop the GLFW_KEY_ prefix: " + quote(token.substr(kPrefix.size())) +
                 ")");
        std::string upper(token);
        for (char& c : upper)
            if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
        if (keyFromName(upper))
            fail("unknown key " + quote(token) + " (key names are upper case: " + quote(upper) + ")");
        fail("unknown key " + quote(token) +
             " (GLFW key names without the GLFW_KEY_ prefix, e.g. SPACE, W, LEFT_SHIFT)");
    }

    MouseButton parseMouseButton(std::string_view token) const {
        if (token == "left") return MouseButton::Left;
        if (token == "right") return MouseButton::Right;
        if (token == "middle") return MouseButton::Middle;
        fail("unknown mouse button " + quote(token) + " (expected left, right or middle)");
    }

    GamepadAxis parseAxis(std::string_view token) const {
        if (const auto axis = gamepadAxisFromName(token)) return *axis;
        fail("unknown gamepad axis " + quote(token) +
             " (expected left_x, left_y, right_x, right_y, left_trigger or right_trigger)");
    }

    GamepadButton parseButton(std::string_view token) const {
        if (const auto button = gamepadButtonFromName(token)) return *button;
        fail("unknown gamepad button " + quote(token) +
             " (expected a, b, x, y, left_bumper, right_bumper, back, start, guide, left_thumb, right_thumb, "
             "dpad_up, dpad_right, dpad_down or dpad_left)");
    }

    std::string_view m_fileName;
    int m_line;
    const std::vector<std::string_view>& m_tokens;
};

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};

} // namespace

std::string actWords(const Actions& a) {
    std::string out;
    const auto add = [&](const std::string& word) {
        if (!out.empty()) out += ' ';
        out += word;
    };
    if (a.move != glm::vec2(0.0f)) add("move=" + exactFloat(a.move.x) + "," + exactFloat(a.move.y));
    if (a.yawDelta != 0.0f) add("yaw=" + exactFloat(a.yawDelta));
    if (a.pitchDelta != 0.0f) add("pitch=" + exactFloat(a.pitchDelta));
    if (a.selectDelta != 0) add("select=" + std::to_string(a.selectDelta));
    if (a.selectSlot >= 0) add("slot=" + std::to_string(a.selectSlot));
    if (a.teleport)
        add("teleport=" + exactFloat(a.teleport->x) + "," + exactFloat(a.teleport->y) + "," +
            exactFloat(a.teleport->z));
    if (a.lookAbsolute) add("look=" + exactFloat(a.lookAbsolute->x) + "," + exactFloat(a.lookAbsolute->y));
    for (const ActFlag& f : kActFlags)
        if (a.*f.field) add(std::string(f.name));
    return out;
}

std::vector<ScriptEvent> parseScript(std::string_view text, std::string_view fileName) {
    std::vector<ScriptEvent> events;
    std::vector<std::string_view> tokens;
    int lineNumber = 0;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        if (lineNumber == INT_MAX)
            throw ScriptError(std::string(fileName) + ": more than " + std::to_string(INT_MAX) + " lines");
        ++lineNumber;
        const auto where = [&] { return std::string(fileName) + ":" + std::to_string(lineNumber) + ": "; };
        if (end - start > kMaxScriptLineBytes)
            throw ScriptError(where() + "line of " + std::to_string(end - start) + " bytes, longer than the " +
                              std::to_string(kMaxScriptLineBytes) + " a script line may have");
        tokenize(text.substr(start, end - start), tokens);
        if (!tokens.empty()) {
            if (events.size() == kMaxScriptEvents)
                throw ScriptError(where() + "more than " + std::to_string(kMaxScriptEvents) +
                                  " events; a script may have at most that many");
            events.push_back(LineParser(fileName, lineNumber, tokens).parse());
        }
        start = end + 1;
    }
    // Stable, so events that share a tick keep their file order (a press before its release).
    std::stable_sort(events.begin(), events.end(),
                     [](const ScriptEvent& a, const ScriptEvent& b) { return a.tick < b.tick; });
    return events;
}

std::string readScriptText(const std::string& path) {
    errno = 0;
    const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file) throw ScriptError(path + ": cannot open: " + std::generic_category().message(errno));
    std::string text;
    std::array<char, 1 << 16> buffer;
    std::size_t n = 0;
    // One byte past the limit is enough to know the file is too large; an endless file (/dev/zero, a
    // pipe) is refused after reading that much, never held whole.
    while (text.size() <= kMaxScriptBytes &&
           (n = std::fread(buffer.data(), 1, std::min(buffer.size(), kMaxScriptBytes + 1 - text.size()), file.get())) >
               0)
        text.append(buffer.data(), n);
    // A directory opens fine on Linux and fails on the first read.
    if (std::ferror(file.get())) throw ScriptError(path + ": cannot read: " + std::generic_category().message(errno));
    if (text.size() > kMaxScriptBytes)
        throw ScriptError(path + ": larger than " + std::to_string(kMaxScriptBytes >> 20) + " MiB (" +
                          std::to_string(kMaxScriptBytes) + " bytes), the most a script may be");
    return text;
}

std::vector<ScriptEvent> loadScript(const std::string& path) { return parseScript(readScriptText(path), path); }

LateEvents eventsFrom(const std::vector<ScriptEvent>& events, std::uint64_t tick) {
    LateEvents late;
    for (const ScriptEvent& e : events) {
        if (e.tick < tick) continue;
        late.firstLine = late.count == 0 ? e.line : std::min(late.firstLine, e.line);
        ++late.count;
    }
    return late;
}

} // namespace input
