#include "app/session.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "game/state_io.h"

namespace app {

namespace {
game::GameDef gameDef(const Options& o) {
    game::GameDef def;
    def.terrain.seed = o.seed;
    def.terrain.kind = o.terrain;
    return def;
}
} // namespace

Session::Session(const Options& options) : m_options(options), m_state(gameDef(options)) {
    if (!options.script.empty()) m_script = input::loadScript(options.script);
}

AppRequests Session::step() {
    while (m_next < m_script.size() && m_script[m_next].tick <= m_state.tick) {
        m_mapper.handle(m_script[m_next].event);
        ++m_next;
    }
    input::Actions actions = m_mapper.takeTickActions(static_cast<float>(tickSeconds()));
    if (m_pauseToggle) {
        actions.togglePause = !actions.togglePause;
        m_pauseToggle = false;
    }
    game::tick(m_state, actions, tickSeconds(), m_commands);
    m_commands = {};
    return {actions.screenshot, actions.toggleOverlay, actions.toggleHelp, actions.interact};
}

void Session::queue(const std::vector<game::PendulumCommand>& commands) {
    m_commands.pendulum.insert(m_commands.pendulum.end(), commands.begin(), commands.end());
}

void Session::queue(const std::vector<game::HairCommand>& commands) {
    m_commands.hair.insert(m_commands.hair.end(), commands.begin(), commands.end());
}

void Session::writeDump(const std::string& path) const {
    // Write beside the target and rename, so a failure never leaves a half-written file in its place.
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error("cannot write state dump " + path);
        out << game::dumpState(m_state).dump(2) << '\n';
        if (!out.flush()) throw std::runtime_error("cannot write state dump " + path);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error("cannot write state dump " + path + ": " + ec.message());
    }
}

} // namespace app
