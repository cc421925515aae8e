// The game-state fuzzer's harness, shared by the libFuzzer target (fuzz_game.cpp, sanitizer build) and a
// seeded run in unit_tests (tests/game/test_game_fuzz.cpp, Release build). Bytes become a script of any
// command with extreme values (keys, mouse, gamepad, teleport, look) plus panel edits (pendulum and hair
// parameters), written as script text and parsed like a player's script; the game runs it tick by tick
// through the same input mapping as the window, and then:
//   - game::checkInvariants holds after every tick (finite, inside the border, valid indices);
//   - the state saves (WorldStore::toImage: the saver's own read-back check included) and loads from those
//     bytes with no warning to the same state hash.
// Any violation prints what broke and aborts, which libFuzzer and GoogleTest both report as a failure.
// Objects are small (16 strands of 4 nodes) so that thousands of inputs run a second.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "game/game_state.h"
#include "game/state_io.h"
#include "input/mapper.h"
#include "input/script.h"
#include "save/world_store.h"

namespace gamefuzz {

[[noreturn]] inline void broken(const std::string& what, const std::string& script) {
    std::fprintf(stderr, "game fuzz: %s\nscript:\n%s\n", what.c_str(), script.c_str());
    std::abort();
}

class Bytes {
public:
    Bytes(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
    bool empty() const { return m_at >= m_size; }
    std::uint8_t byte() { return m_at < m_size ? m_data[m_at++] : 0; }
    // Mostly the values that break things (zero, huge, tiny, the border and past it), sometimes any float.
    double extreme() {
        static constexpr double kValues[] = {0.0,     1.0,  -1.0, 0.5,    1e-30,  -1e-30,  1e30, -1e30,   3.4e38,
                                             -3.4e38, 1e6,  -1e6, 8192.0, 8193.0, -8192.5, 1e9,  127.9,   128.0,
                                             -64.0,   89.0, 90.0, -90.0,  179.0,  360.0,   1e-7, 65536.0, 0.25};
        const std::uint8_t pick = byte();
        if (pick < 200) return kValues[pick % (sizeof kValues / sizeof kValues[0])];
        std::uint32_t bits = 0;
        for (int i = 0; i < 4; ++i) bits = (bits << 8) | byte();
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return std::isfinite(f) ? f : 0.0;
    }
    double within(double lo, double hi) { return std::fmin(hi, std::fmax(lo, extreme())); }

private:
    const std::uint8_t* m_data;
    std::size_t m_size, m_at = 0;
};

inline std::string number(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

struct Input {
    std::string script;                       // script text, parsed by input::parseScript
    std::vector<game::TickCommands> commands; // panel edits, per tick
    int ticks = 1;
};

inline Input decode(const std::uint8_t* data, std::size_t size) {
    static constexpr const char* kKeys[] = {"W", "A", "S", "D", "SPACE", "LEFT_SHIFT", "LEFT_CONTROL", "F",      "E",
                                            "Q", "1", "7", "8", "9",     "F2",         "F3",           "ESCAPE", "F1"};
    static constexpr const char* kAxes[] = {"left_x", "left_y", "right_x", "right_y", "left_trigger", "right_trigger"};
    static constexpr const char* kButtons[] = {
        "a",     "b",          "x",           "y",       "left_bumper", "right_bumper", "back",
        "start", "left_thumb", "right_thumb", "dpad_up", "dpad_down",   "dpad_left"};
    Bytes in(data, size);
    Input out;
    out.ticks = 1 + in.byte() % 48;
    out.commands.resize(static_cast<std::size_t>(out.ticks));
    int tick = 0;
    const auto line = [&](const std::string& text) { out.script += std::to_string(tick) + " " + text + "\n"; };
    while (!in.empty()) {
        const std::uint8_t op = in.byte();
        switch (op % 12) {
        case 0:
            line(std::string("key ") + kKeys[in.byte() % std::size(kKeys)] + (in.byte() & 1 ? " down" : " up"));
            break;
        case 1:
            line("mouse_move " + number(in.within(-3.4e38, 3.4e38)) + " " + number(in.within(-3.4e38, 3.4e38)));
            break;
        case 2: {
            static constexpr const char* kMouse[] = {"left", "right", "middle"};
            line(std::string("mouse_button ") + kMouse[in.byte() % 3] + (in.byte() & 1 ? " down" : " up"));
            break;
        }
        case 3:
            line("scroll " + number(in.within(-3.4e38, 3.4e38)));
            break;
        case 4: {
            const std::size_t a = in.byte() % std::size(kAxes);
            line(std::string("gamepad_axis ") + kAxes[a] + " " + number(a >= 4 ? in.within(0, 1) : in.within(-1, 1)));
            break;
        }
        case 5:
            line(std::string("gamepad_button ") + kButtons[in.byte() % std::size(kButtons)] +
                 (in.byte() & 1 ? " down" : " up"));
            break;
        case 6: {
            const double x = in.within(-3.4e38, 3.4e38), y = in.within(-3.4e38, 3.4e38), z = in.within(-3.4e38, 3.4e38);
            line("teleport " + number(x) + " " + number(y) + " " + number(z));
            break;
        }
        case 7:
            line("look " + number(in.within(-3.4e38, 3.4e38)) + " " + number(in.within(-90, 90)));
            break;
        case 8: {
            game::PendulumCommand c;
            c.set = in.byte() % 3;
            c.op = static_cast<game::PendulumCommand::Op>(in.byte() % 3);
            c.def.releaseDegrees = in.extreme();
            c.def.length = in.extreme();
            c.def.gravity = in.extreme();
            c.def.stepMultiplier = in.extreme();
            for (auto& m : c.def.methods) m = static_cast<physics::Method>(in.byte() % 8);
            out.commands[static_cast<std::size_t>(tick)].pendulum.push_back(c);
            break;
        }
        case 9: {
            game::HairCommand c;
            c.ball = in.byte() % 4;
            c.def.radius = static_cast<float>(in.extreme());
            c.def.spinRate = static_cast<float>(in.extreme());
            c.def.colour.r = static_cast<float>(in.extreme());
            c.def.hair.strands = 1 + in.byte() % 32;
            c.def.hair.nodesPerStrand = 2 + in.byte() % 6;
            c.def.hair.strandLength = static_cast<float>(in.extreme());
            c.def.hair.dampingPerSecond = static_cast<float>(in.extreme());
            c.def.hair.gravity = static_cast<float>(in.extreme());
            c.def.hair.iterations = static_cast<int>(in.byte() % 8);
            c.def.hair.patchHalfAngle = static_cast<float>(in.extreme());
            out.commands[static_cast<std::size_t>(tick)].hair.push_back(c);
            break;
        }
        case 10: // the time of day: the tick takes 0 <= h < 24 and drops the rest, like a refused panel edit
            out.commands[static_cast<std::size_t>(tick)].timeOfDay = in.extreme();
            break;
        default:
            tick = std::min(tick + 1 + in.byte() % 4, out.ticks - 1);
            break;
        }
    }
    return out;
}

inline game::GameDef smallWorld(bool flat) {
    game::GameDef def;
    def.terrain.kind = flat ? world::TerrainKind::Flat : world::TerrainKind::Default;
    def.ballDef.hair.strands = 16;
    def.ballDef.hair.nodesPerStrand = 4;
    return def;
}

// Runs one input; aborts (naming what broke, with the script) on any violation.
inline void runOne(const std::uint8_t* data, std::size_t size) {
    const Input in = decode(data, size);
    std::vector<input::ScriptEvent> events;
    try {
        events = input::parseScript(in.script, "fuzz.script");
    } catch (const input::ScriptError& e) {
        broken(std::string("the harness wrote a script line the parser refuses: ") + e.what(), in.script);
    }
    // The default terrain in a quarter of the inputs: its blocks cost a noise evaluation each (no chunk is
    // loaded without a renderer), the flat one almost nothing.
    game::GameState state(smallWorld(size == 0 || (data[0] & 0xC0) != 0xC0));
    input::InputMapper mapper;
    constexpr double kDt = 1.0 / 60.0;
    std::size_t next = 0;
    for (int t = 0; t < in.ticks; ++t) {
        while (next < events.size() && events[next].tick <= state.tick) mapper.handle(events[next++].event);
        game::tick(state, mapper.takeTickActions(static_cast<float>(kDt)), kDt,
                   in.commands[static_cast<std::size_t>(t)]);
        if (const std::string why = game::checkInvariants(state); !why.empty())
            broken("after tick " + std::to_string(state.tick) + ": " + why, in.script);
    }
    // Save what the game reached, load it back: nothing refused, nothing skipped, the same state.
    const save::Snapshot snapshot = save::takeSnapshot(state);
    std::vector<unsigned char> image;
    try {
        image = save::WorldStore::toImage(snapshot);
    } catch (const save::WorldFileError& e) {
        broken(std::string("the game reached a state it cannot save: ") + e.what(), in.script);
    }
    try {
        auto store = save::WorldStore::openImage(image, "fuzz.mcworld");
        const game::GameState loaded = save::restore(store->load());
        if (!store->warnings().empty())
            broken("the saved world loads with a warning: " + store->warnings()[0], in.script);
        if (game::stateHash(loaded) != snapshot.stateHash)
            broken("the loaded world's hash differs from the saved one", in.script);
        if (const std::string why = game::checkInvariants(loaded); !why.empty())
            broken("the loaded world: " + why, in.script);
    } catch (const save::WorldFileError& e) {
        broken(std::string("the saved world does not load: ") + e.what(), in.script);
    }
}

} // namespace gamefuzz
