#include "platform/glfw_window.h"

#include "input/gamepad_mappings.h"

// The platform opens the context and issues no GL call: GLFW must not declare GL either (GL and GLEW are
// poisoned in this layer, src/CMakeLists.txt).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>

namespace platform {

namespace {
int g_liveWindows = 0;
std::string g_lastGlfwError;

void onGlfwError(int code, const char* description) {
    g_lastGlfwError = std::string(description ? description : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}

// input::GamepadAxis and GamepadButton follow GLFW's order, and key codes are GLFW's own values.
static_assert(GLFW_GAMEPAD_AXIS_LAST + 1 == static_cast<int>(input::GamepadAxis::Count));
static_assert(GLFW_GAMEPAD_BUTTON_LAST + 1 == static_cast<int>(input::GamepadButton::Count));
} // namespace

struct GlfwCallbacks {
    static GlfwWindow* self(GLFWwindow* w) { return static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w)); }
    static void key(GLFWwindow* w, int key, int, int action, int) {
        if (key == GLFW_KEY_UNKNOWN || action == GLFW_REPEAT) return;
        self(w)->m_events.push_back(input::KeyEvent{key, action == GLFW_PRESS});
    }
    static void mouseButton(GLFWwindow* w, int button, int action, int) {
        input::MouseButton b;
        switch (button) {
        case GLFW_MOUSE_BUTTON_LEFT:
            b = input::MouseButton::Left;
            break;
        case GLFW_MOUSE_BUTTON_RIGHT:
            b = input::MouseButton::Right;
            break;
        case GLFW_MOUSE_BUTTON_MIDDLE:
            b = input::MouseButton::Middle;
            break;
        default:
            return;
        }
        self(w)->m_events.push_back(input::MouseButtonEvent{b, action == GLFW_PRESS});
    }
    static void cursor(GLFWwindow* w, double x, double y) {
        GlfwWindow* s = self(w);
        if (s->m_haveCursor && s->m_captured) {
            s->m_events.push_back(
                input::MouseMoveEvent{static_cast<float>(x - s->m_lastX), static_cast<float>(y - s->m_lastY)});
        }
        s->m_lastX = x;
        s->m_lastY = y;
        s->m_haveCursor = true;
    }
    static void scroll(GLFWwindow* w, double, double dy) {
        self(w)->m_events.push_back(input::ScrollEvent{static_cast<float>(dy)});
    }
};

bool GlfwWindow::displayAvailable() {
    const char* x = std::getenv("DISPLAY");
    const char* wl = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (wl && *wl);
}

GlfwWindow::GlfwWindow(const WindowDef& def) {
    glfwSetErrorCallback(onGlfwError);
    if (g_liveWindows == 0 && !glfwInit()) {
        throw WindowError("cannot open a window: " + g_lastGlfwError +
                          (displayAvailable() ? "" : "; no display found (DISPLAY is not set): try --headless"));
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    m_window = glfwCreateWindow(def.width, def.height, def.title.c_str(), nullptr, nullptr);
    if (!m_window) {
        if (g_liveWindows == 0) glfwTerminate();
        throw WindowError("cannot create a window with OpenGL 3.3 core: " + g_lastGlfwError);
    }
    ++g_liveWindows;
    glfwMakeContextCurrent(m_window);
    glfwSwapInterval(def.vsync ? 1 : 0);
    glfwSetWindowUserPointer(m_window, this);
    glfwSetKeyCallback(m_window, GlfwCallbacks::key);
    glfwSetMouseButtonCallback(m_window, GlfwCallbacks::mouseButton);
    glfwSetCursorPosCallback(m_window, GlfwCallbacks::cursor);
    glfwSetScrollCallback(m_window, GlfwCallbacks::scroll);
}

GlfwWindow::~GlfwWindow() {
    glfwDestroyWindow(m_window);
    if (--g_liveWindows == 0) glfwTerminate();
}

glm::ivec2 GlfwWindow::framebufferSize() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(m_window, &w, &h);
    return {w, h};
}

void GlfwWindow::present() { glfwSwapBuffers(m_window); }

std::vector<input::InputEvent> GlfwWindow::pollEvents() {
    glfwPollEvents();
    std::vector<input::InputEvent> out;
    out.swap(m_events);
    return out;
}

input::GamepadState GlfwWindow::pollGamepad() {
    input::GamepadState state;
    // Hot-plug: keep the pad we had while it stays connected, else take the first one present.
    if (m_joystick < 0 || !glfwJoystickIsGamepad(m_joystick)) {
        m_joystick = -1;
        m_gamepadName.clear();
        for (int j = GLFW_JOYSTICK_1; j <= GLFW_JOYSTICK_LAST; ++j) {
            if (glfwJoystickIsGamepad(j)) {
                m_joystick = j;
                const char* name = glfwGetGamepadName(j);
                m_gamepadName = input::padLabel(true, true, name ? name : "");
                break;
            }
        }
        for (int j = GLFW_JOYSTICK_1; m_joystick < 0 && j <= GLFW_JOYSTICK_LAST; ++j) {
            if (glfwJoystickPresent(j)) {
                const char* name = glfwGetJoystickName(j);
                m_gamepadName = input::padLabel(true, false, name ? name : "");
                break;
            }
        }
    }
    GLFWgamepadstate raw;
    if (m_joystick >= 0 && glfwGetGamepadState(m_joystick, &raw)) {
        state.connected = true;
        for (std::size_t i = 0; i < state.axes.size(); ++i) state.axes[i] = raw.axes[i];
        for (std::size_t i = 0; i < state.buttons.size(); ++i) state.buttons[i] = raw.buttons[i] == GLFW_PRESS;
    }
    return state;
}

std::vector<std::string> GlfwWindow::addGamepadMappings(const std::vector<std::string>& lines) {
    std::vector<std::string> refused;
    for (const std::string& line : lines) {
        if (glfwUpdateGamepadMappings(line.c_str()) == GLFW_TRUE) continue;
        const char* why = nullptr;
        glfwGetError(&why);
        const std::size_t comma = line.find(',');
        const std::size_t nameEnd = line.find(',', comma + 1);
        refused.push_back(line.substr(0, comma) + " (" + line.substr(comma + 1, nameEnd - comma - 1) +
                          "): " + (why ? why : "refused by GLFW"));
    }
    m_joystick = -1; // look again: a connected pad may have a mapping now
    return refused;
}

bool GlfwWindow::shouldClose() const { return glfwWindowShouldClose(m_window) != 0; }
void GlfwWindow::requestClose() { glfwSetWindowShouldClose(m_window, GLFW_TRUE); }
bool GlfwWindow::focused() const { return glfwGetWindowAttrib(m_window, GLFW_FOCUSED) != 0; }
double GlfwWindow::time() const { return glfwGetTime(); }

void GlfwWindow::setSize(int width, int height) {
    int w = 0, h = 0;
    glfwGetWindowSize(m_window, &w, &h);
    if (w != width || h != height) glfwSetWindowSize(m_window, width, height);
}

void GlfwWindow::setVsync(bool on) { glfwSwapInterval(on ? 1 : 0); }

void GlfwWindow::setCursorCaptured(bool captured) {
    if (captured == m_captured) return;
    m_captured = captured;
    glfwSetInputMode(m_window, GLFW_CURSOR, captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
    if (captured && glfwRawMouseMotionSupported()) glfwSetInputMode(m_window, GLFW_RAW_MOUSE_MOTION, GLFW_TRUE);
    // Motion is measured from where the cursor is now: the mode change itself is not a movement.
    glfwGetCursorPos(m_window, &m_lastX, &m_lastY);
    m_haveCursor = true;
}

} // namespace platform
