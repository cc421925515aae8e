// Which object panel is open, shared by the window and the headless runner: opened by the interact
// action on the object the player looks at, closed by the same action, by Esc, or when the object goes.
#pragma once
#include <optional>

#include "render/scene_renderer.h"
#include "session/session.h"
#include "ui/ui.h"

namespace app {

class ObjectPanels {
public:
    // Opens the panel of the targeted object, or closes the open one.
    void interact(const game::GameState& state);
    void close() {
        m_pendulum.reset();
        m_hair.reset();
    }
    bool anyOpen() const { return m_pendulum.has_value() || m_hair.has_value(); }
    // Draws the open panel and queues its edits into the session. readOnly (a replay's timeline): the panel shows
    // the object's figures and parameters at the tick on screen, its controls are disabled and nothing is queued.
    void show(session::Session& session, bool readOnly = false);

private:
    std::optional<ui::PendulumPanel> m_pendulum;
    std::optional<ui::HairPanel> m_hair;
};

} // namespace app
