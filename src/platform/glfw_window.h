// The platform: a GLFW window with a 3.3 core context, its raw input turned into
// input::InputEvent values (the same events a headless script produces), and the first connected
// gamepad polled through GLFW's gamepad mappings, with hot-plug. It makes the context current and draws
// nothing: GL's entry points are loaded and used by render (render::loadGl, which the window runner calls),
// and neither layer includes the other (docs/ARCHITECTURE.md).
#pragma once
#include <glm/vec2.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "input/events.h"

struct GLFWwindow;

namespace platform {

// No window: no display, or no OpenGL 3.3 core context on it. Exit code 1.
class WindowError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct WindowDef {
    int width = 1280; // pixels
    int height = 720; // pixels
    bool vsync = true;
    std::string title = "Minecrappy";
};

class GlfwWindow final {
public:
    explicit GlfwWindow(const WindowDef& def); // throws WindowError (no display, no GL 3.3)
    ~GlfwWindow();
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    glm::ivec2 framebufferSize() const;
    // Finishes the frame: swaps buffers.
    void present();

    // Polls the window system; returns the events since the last call, in order.
    std::vector<input::InputEvent> pollEvents();
    // The first connected gamepad with a known mapping (connected = false if none).
    input::GamepadState pollGamepad();
    // The pad for the F3 overlay: "NAME (mapped)" for the gamepad in use, "NAME (no mapping)" for a joystick
    // GLFW has no gamepad mapping for (it cannot be used until one is added), empty with none connected.
    std::string gamepadName() const { return m_gamepadName; }
    // Hands SDL-format mapping lines (input::parseGamepadMappings' good ones) to GLFW, one at a time; returns
    // "GUID (NAME): GLFW's reason" for each line GLFW refused. Connected pads pick the mappings up at once.
    std::vector<std::string> addGamepadMappings(const std::vector<std::string>& lines);

    bool shouldClose() const;
    void requestClose();
    // Captures the cursor for mouse look (hidden, unbounded motion) or releases it for menus.
    void setCursorCaptured(bool captured);
    bool cursorCaptured() const { return m_captured; }
    bool focused() const;
    void setSize(int width, int height);
    void setVsync(bool on);
    double time() const;
    GLFWwindow* handle() const { return m_window; }

    // True when there is no display to open a window on (checked without creating one).
    static bool displayAvailable();

private:
    friend struct GlfwCallbacks;
    GLFWwindow* m_window = nullptr;
    std::vector<input::InputEvent> m_events;
    bool m_captured = false;
    bool m_haveCursor = false;
    double m_lastX = 0.0, m_lastY = 0.0;
    int m_joystick = -1;
    std::string m_gamepadName;
};

} // namespace platform
