// The settings panel: every player setting with a widget, edited live, and a Save button. It only
// edits a Settings value and raises flags; the caller applies the changes (mapper config, scene,
// window, tick rate) and writes the file with session::saveSettings, so this layer never touches a file.
// Rebinding: click an action's button, then press the new key (or pad button); Escape cancels.
#pragma once
#include <optional>
#include <string>

#include "session/settings.h"

namespace ui {

struct SettingsPanel {
    session::Settings edit;     // what the controls show; the caller initialises it with the settings in effect
    std::string filePath;       // shown under the Save button; empty: "not saved (--settings none)"
    std::string overriddenNote; // e.g. "--fov and --size override the file for this run"; shown when not empty
    std::string status;         // result of the last save, set by the caller
    bool changed = false;       // set by the panel when edit changed; the caller applies it and clears it
    bool saveRequested = false; // set by Save; the caller saves and clears it

    // Rebinding in progress: which binding waits for a key or button (-1: none).
    int capturingKey = -1; // index into the panel's key rows
    int capturingPad = -1; // index into the panel's pad rows
    // Fed by the caller (feedSettingsPanelKey/Button) or read from ImGui's KeysDown by the panel.
    std::optional<int> capturedKey;
    std::optional<int> capturedButton; // input::GamepadButton as int
};

// While a rebind waits, the window passes each key press (GLFW code) and each newly pressed pad button
// here; the next showSettingsPanel applies it. Returns true when the press was consumed by a rebind,
// so the caller should not also treat it as a game action.
bool feedSettingsPanelKey(SettingsPanel& panel, int glfwKey);
bool feedSettingsPanelButton(SettingsPanel& panel, int gamepadButton);
// True while a binding waits for its key or button.
bool settingsPanelCapturing(const SettingsPanel& panel);

void showSettingsPanel(SettingsPanel& panel, bool* open);

} // namespace ui
