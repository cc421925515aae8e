#include "session/paths.h"

#include <cstdlib>

namespace session {

std::filesystem::path xdgBase(const char* variable, std::string_view homeFallback) {
    // "If an implementation encounters a relative path in any of these variables it should consider the path
    // invalid and ignore it" (XDG Base Directory Specification 0.8).
    const char* value = std::getenv(variable);
    if (value && *value && std::filesystem::path(value).is_absolute()) return value;
    const char* home = std::getenv("HOME");
    return std::filesystem::path(home && *home ? home : ".") / homeFallback;
}

std::filesystem::path defaultSettingsPath() {
    return xdgBase("XDG_CONFIG_HOME", ".config") / "minecrappy" / "settings.toml";
}

std::filesystem::path defaultGamepadMappingsPath() {
    return xdgBase("XDG_CONFIG_HOME", ".config") / "minecrappy" / "gamecontrollerdb.txt";
}

std::filesystem::path defaultWorldsFolder() {
    return xdgBase("XDG_DATA_HOME", ".local/share") / "minecrappy" / "worlds";
}

} // namespace session
