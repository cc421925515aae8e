// Where the game keeps a player's files, per the XDG Base Directory specification: settings under
// $XDG_CONFIG_HOME (default ~/.config), worlds under $XDG_DATA_HOME (default ~/.local/share). The one place
// these variables are read. The spec's rule for a relative value (it is invalid and must be ignored) applies
// to both, and a missing HOME falls back to the working folder.
#pragma once
#include <filesystem>
#include <string_view>

namespace session {

// $XDG_CONFIG_HOME/minecrappy/settings.toml, else ~/.config/minecrappy/settings.toml, else ./settings.toml.
std::filesystem::path defaultSettingsPath();
// $XDG_CONFIG_HOME/minecrappy/gamecontrollerdb.txt (same rule): extra gamepad mappings, read when present.
std::filesystem::path defaultGamepadMappingsPath();
// $XDG_DATA_HOME/minecrappy/worlds, else ~/.local/share/minecrappy/worlds, else ./.local/share/minecrappy/worlds.
std::filesystem::path defaultWorldsFolder();

// The base folder named by the environment variable `variable` when it is set to an absolute path, else
// $HOME/`homeFallback`, else the working folder joined with `homeFallback`. Exposed for the tests.
std::filesystem::path xdgBase(const char* variable, std::string_view homeFallback);

} // namespace session
