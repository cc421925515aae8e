#include "game/command_text.h"

#include "core/quote.h"

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace game {

namespace {

[[noreturn]] void bad(std::string_view word, const std::string& why) {
    std::string message = "'";
    message += word;
    message += "': ";
    message += why;
    throw std::invalid_argument(message);
}

template <typename T>
T number(std::string_view word, std::string_view text) {
    T v{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || end != text.data() + text.size()) bad(word, "not a number of the field's type");
    if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(v)) bad(word, "not a finite number");
    }
    return v;
}

// Splits "key=value"; a word without '=' is an error.
std::pair<std::string_view, std::string_view> field(std::string_view word) {
    const std::size_t eq = word.find('=');
    if (eq == std::string_view::npos) bad(word, "expected FIELD=VALUE");
    return {word.substr(0, eq), word.substr(eq + 1)};
}

} // namespace

std::vector<std::string> pendulumCommandWords(const PendulumCommand& c) {
    switch (c.op) {
    case PendulumCommand::Op::Release:
        return {"release"};
    case PendulumCommand::Op::Reset:
        return {"reset"};
    case PendulumCommand::Op::SetDef:
        break;
    }
    std::string methods;
    for (const physics::Method m : c.def.methods) {
        if (!methods.empty()) methods += ',';
        methods += physics::methodName(m);
    }
    return {"set",
            "release=" + core::shortestText(c.def.releaseDegrees),
            "length=" + core::shortestText(c.def.length),
            "gravity=" + core::shortestText(c.def.gravity),
            "step=" + core::shortestText(c.def.stepMultiplier),
            "methods=" + methods};
}

PendulumCommand pendulumCommandFrom(std::uint64_t index, const std::vector<std::string>& words) {
    PendulumCommand c;
    c.set = static_cast<std::size_t>(index);
    if (words.empty()) throw std::invalid_argument("expected set, release or reset after the index");
    const std::string& op = words[0];
    if (op == "release" || op == "reset") {
        if (words.size() > 1) bad(words[1], op + " takes no fields");
        c.op = op == "release" ? PendulumCommand::Op::Release : PendulumCommand::Op::Reset;
        return c;
    }
    if (op != "set") bad(op, "expected set, release or reset");
    c.op = PendulumCommand::Op::SetDef;
    for (std::size_t i = 1; i < words.size(); ++i) {
        const auto [key, value] = field(words[i]);
        if (key == "release") {
            c.def.releaseDegrees = number<double>(words[i], value);
        } else if (key == "length") {
            c.def.length = number<double>(words[i], value);
        } else if (key == "gravity") {
            c.def.gravity = number<double>(words[i], value);
        } else if (key == "step") {
            c.def.stepMultiplier = number<double>(words[i], value);
        } else if (key == "methods") {
            const auto parts = core::splitAt(value, ',');
            if (parts.size() != c.def.methods.size()) bad(words[i], "expected 4 method names separated by commas");
            for (std::size_t k = 0; k < parts.size(); ++k) {
                const auto m = physics::methodFromName(parts[k]);
                if (!m) bad(words[i], "unknown method '" + std::string(parts[k]) + "'");
                c.def.methods[k] = *m;
            }
        } else {
            bad(words[i], "unknown field (expected release, length, gravity, step or methods)");
        }
    }
    return c;
}

std::vector<std::string> hairCommandWords(const HairCommand& c) {
    const HairBallDef& d = c.def;
    const physics::HairParams& h = d.hair;
    return {"radius=" + core::shortestText(d.radius),
            "colour=" + core::shortestText(d.colour.r) + "," + core::shortestText(d.colour.g) + "," +
                core::shortestText(d.colour.b),
            "spin=" + core::shortestText(d.spinRate),
            "strands=" + std::to_string(h.strands),
            "nodes=" + std::to_string(h.nodesPerStrand),
            "length=" + core::shortestText(h.strandLength),
            "damping=" + core::shortestText(h.dampingPerSecond),
            "gravity=" + core::shortestText(h.gravity),
            "iterations=" + std::to_string(h.iterations),
            "substeps=" + std::to_string(h.substeps),
            "patch=" + core::shortestText(h.patchHalfAngle),
            "seed=" + std::to_string(h.seed),
            "max_substep=" + core::shortestText(h.maxSubstepSeconds),
            "sleep_speed=" + core::shortestText(h.sleepSpeed),
            "sleep_delay=" + core::shortestText(h.sleepDelay),
            "velocity_correction=" + core::shortestText(h.velocityCorrection),
            "method=" + std::string(physics::hairMethodName(h.method)),
            std::string("host_collision=") + (h.hostCollision ? "true" : "false")};
}

HairCommand hairCommandFrom(std::uint64_t index, const std::vector<std::string>& words) {
    HairCommand c;
    c.ball = static_cast<std::size_t>(index);
    HairBallDef& d = c.def;
    physics::HairParams& h = d.hair;
    for (const std::string& word : words) {
        const auto [key, value] = field(word);
        if (key == "radius") {
            d.radius = number<float>(word, value);
        } else if (key == "colour") {
            const auto parts = core::splitAt(value, ',');
            if (parts.size() != 3) bad(word, "expected R,G,B");
            d.colour = {number<float>(word, parts[0]), number<float>(word, parts[1]), number<float>(word, parts[2])};
        } else if (key == "spin") {
            d.spinRate = number<float>(word, value);
        } else if (key == "strands") {
            h.strands = number<int>(word, value);
        } else if (key == "nodes") {
            h.nodesPerStrand = number<int>(word, value);
        } else if (key == "length") {
            h.strandLength = number<float>(word, value);
        } else if (key == "damping") {
            h.dampingPerSecond = number<float>(word, value);
        } else if (key == "gravity") {
            h.gravity = number<float>(word, value);
        } else if (key == "iterations") {
            h.iterations = number<int>(word, value);
        } else if (key == "substeps") {
            h.substeps = number<int>(word, value);
        } else if (key == "patch") {
            h.patchHalfAngle = number<float>(word, value);
        } else if (key == "seed") {
            h.seed = number<std::uint64_t>(word, value);
        } else if (key == "max_substep") {
            h.maxSubstepSeconds = number<float>(word, value);
        } else if (key == "sleep_speed") {
            h.sleepSpeed = number<float>(word, value);
        } else if (key == "sleep_delay") {
            h.sleepDelay = number<float>(word, value);
        } else if (key == "velocity_correction") {
            h.velocityCorrection = number<float>(word, value);
        } else if (key == "method") {
            const auto m = physics::hairMethodFromName(value);
            if (!m) bad(word, "unknown hair method");
            h.method = *m;
        } else if (key == "host_collision") {
            if (value != "true" && value != "false") bad(word, "expected true or false");
            h.hostCollision = value == "true";
        } else {
            bad(word, "unknown field (expected radius, colour, spin, strands, nodes, length, damping, gravity, "
                      "iterations, substeps, patch, seed, max_substep, sleep_speed, sleep_delay, "
                      "velocity_correction, method or host_collision)");
        }
    }
    return c;
}

HotbarCommand hotbarCommandFrom(std::uint64_t slot, const std::string& item) {
    if (slot < 1 || slot > static_cast<std::uint64_t>(kHotbarSize))
        throw std::invalid_argument("slot " + std::to_string(slot) + " is not 1 to " + std::to_string(kHotbarSize));
    const std::optional<Item> parsed = itemFromName(item);
    if (!parsed) {
        std::string names;
        for (const Item& i : everyItem()) names += (names.empty() ? "" : ", ") + std::string(itemName(i));
        throw std::invalid_argument(core::quoteForMessage(item) + " is no block or object (one of " + names + ")");
    }
    return {static_cast<int>(slot) - 1, *parsed};
}

} // namespace game
