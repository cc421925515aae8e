// libFuzzer target: the settings file's text (app/settings.h), parsed from memory as loadSettings() parses a
// file it has read. Parsing must never throw or crash, whatever the bytes: bad values only give warnings.
// Whatever was accepted must survive a round trip through settingsText(): the same settings, and no warning
// but the ones about actions that share a key or button (the settings keep such bindings; found by this
// target once it ran fast enough to reach them).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "session/settings.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const session::SettingsLoad loaded = session::parseSettings(text, "fuzz.toml");
        const session::SettingsLoad again = session::parseSettings(session::settingsText(loaded.settings), "fuzz.toml");
        const std::vector<std::string> conflicts = session::bindingConflicts(loaded.settings);
        if (again.warnings.size() != conflicts.size() || !(again.settings == loaded.settings)) std::abort();
        for (const std::string& w : again.warnings) {
            if (std::none_of(conflicts.begin(), conflicts.end(),
                             [&](const std::string& c) { return w.find(c) != std::string::npos; }))
                std::abort();
        }
    } catch (...) {
        std::abort(); // documented: never throws
    }
    return 0;
}
