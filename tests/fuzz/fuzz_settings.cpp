// libFuzzer target: the settings file (app/settings.h). loadSettings() reads a file, so each input is
// written to a scratch file first. Loading must never throw or crash, whatever the bytes: bad values only
// give warnings. A loaded result must also survive a round trip through settingsText().
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/settings.h"

namespace {

const std::filesystem::path& scratchFile() {
    static const std::filesystem::path path = [] {
        const std::filesystem::path dir =
            std::filesystem::temp_directory_path() / ("mc-fuzz-settings-" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir);
        return dir / "settings.toml";
    }();
    return path;
}

void writeFile(const std::filesystem::path& path, const char* data, std::size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(data, static_cast<std::streamsize>(size));
    if (!out) std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path& file = scratchFile();
    writeFile(file, reinterpret_cast<const char*>(data), size);
    app::SettingsLoad loaded;
    try {
        loaded = app::loadSettings(file);
    } catch (...) {
        std::abort(); // documented: never throws
    }
    if (loaded.created) std::abort(); // the file existed
    // Whatever was accepted must be written back and read again to the same settings, with no warning.
    const std::string text = app::settingsText(loaded.settings);
    writeFile(file, text.data(), text.size());
    try {
        const app::SettingsLoad again = app::loadSettings(file);
        if (!again.warnings.empty() || !(again.settings == loaded.settings)) std::abort();
    } catch (...) {
        std::abort();
    }
    return 0;
}
