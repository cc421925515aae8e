// libFuzzer target: the headless input script parser (input/script.h). Any text must either parse or
// throw input::ScriptError; anything else (another exception, a crash, a sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "input/script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const auto events = input::parseScript(text, "fuzz.script");
        // The documented postconditions: sorted by tick, ticks within range, lines 1-based.
        for (std::size_t i = 0; i < events.size(); ++i) {
            if (events[i].tick > input::kMaxScriptTick || events[i].line < 1) std::abort();
            if (i > 0 && events[i - 1].tick > events[i].tick) std::abort();
            if (i > 0 && events[i - 1].tick == events[i].tick && events[i - 1].line >= events[i].line) std::abort();
        }
    } catch (const input::ScriptError&) {
        // A rejected script is the expected outcome for most inputs.
    }
    return 0;
}
