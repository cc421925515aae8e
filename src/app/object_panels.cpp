#include "app/object_panels.h"

namespace app {

void ObjectPanels::interact(const game::GameState& state) {
    if (anyOpen()) {
        close();
        return;
    }
    const game::Target target = game::targetOf(state);
    if (target.kind == game::Target::Kind::PendulumSet) {
        ui::PendulumPanel panel;
        panel.index = target.index;
        panel.edit = state.pendulumSets[target.index].def();
        m_pendulum = panel;
    } else if (target.kind == game::Target::Kind::HairBall) {
        ui::HairPanel panel;
        panel.index = target.index;
        panel.edit = state.hairBalls[target.index].def();
        m_hair = panel;
    }
}

void ObjectPanels::show(session::Session& session, bool readOnly) {
    const game::GameState& state = session.state();
    if (m_hair) {
        if (m_hair->index >= state.hairBalls.size()) {
            close();
            return;
        }
        m_hair->ball = &state.hairBalls[m_hair->index];
        m_hair->readOnly = readOnly;
        if (readOnly) m_hair->edit = m_hair->ball->def(); // the recording's, at the tick on screen
        bool open = true;
        ui::showHairPanel(*m_hair, &open);
        if (readOnly) m_hair->commands.clear();
        session.queue(m_hair->commands);
        m_hair->commands.clear();
        if (!open) close();
        return;
    }
    if (!m_pendulum) return;
    if (m_pendulum->index >= state.pendulumSets.size()) { // broken while the panel was open
        close();
        return;
    }
    m_pendulum->set = &state.pendulumSets[m_pendulum->index];
    m_pendulum->tickSeconds = session.tickSeconds();
    m_pendulum->readOnly = readOnly;
    if (readOnly) m_pendulum->edit = m_pendulum->set->def();
    bool open = true;
    ui::showPendulumPanel(*m_pendulum, &open);
    if (readOnly) m_pendulum->commands.clear();
    session.queue(m_pendulum->commands);
    m_pendulum->commands.clear();
    if (!open) close();
}

} // namespace app
