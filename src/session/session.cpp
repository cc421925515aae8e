#include "session/session.h"

#include "core/atomic_file.h"
#include "core/log.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "game/state_io.h"

namespace session {

namespace {
game::GameDef gameDef(const Options& o, float hairDetail, std::int64_t hairBudget) {
    game::GameDef def;
    def.hairDetail = hairDetail;
    def.hairBudget = hairBudget;
    def.terrain.seed = o.seed;
    def.terrain.kind = o.terrain;
    return def;
}
} // namespace

Session::Session(const Options& options, const Settings& settings)
    : m_options(options),
      m_state(gameDef(options, hairDetailFraction(settings.hairDetail), hairBudgetPasses(settings))),
      m_mapper(settings.input) {
    if (!options.script.empty()) m_script = input::loadScript(options.script);
    if (!options.world.empty()) openWorld(options.world, options.seed, options.terrain);
}

Session::~Session() {
    if (m_autosaver) {
        for (const auto& e : m_autosaver->flush()) core::logError("%s", e.c_str());
    }
}

std::filesystem::path Session::worldPath() const { return m_autosaver ? m_autosaver->path() : std::filesystem::path(); }

void Session::openWorld(const std::filesystem::path& file, std::uint64_t seedIfNew, world::TerrainKind terrainIfNew) {
    // Open (validating read-only first) before letting go of the current world: a bad file changes nothing.
    auto store = save::WorldStore::open(file, true);
    std::optional<game::GameState> loaded;
    std::vector<std::string> warnings;
    if (!store->isNew()) {
        loaded.emplace(save::restore(store->load()));
        warnings = store->warnings();
    }
    if (m_autosaver) saveNow();
    m_autosaver.reset();
    // Settings of this machine, not of the world.
    const float hairDetail = m_state.def.hairDetail;
    const std::int64_t hairBudget = m_state.def.hairBudget;
    if (loaded) {
        m_state = std::move(*loaded);
        m_state.def.hairDetail = hairDetail;
        m_state.def.hairBudget = hairBudget;
    } else {
        Options o = m_options;
        o.seed = seedIfNew;
        o.terrain = terrainIfNew;
        m_state = game::GameState(gameDef(o, hairDetail, hairBudget));
    }
    m_loadWarnings = std::move(warnings);
    m_autosaver = std::make_unique<Autosaver>(std::move(store));
    if (!loaded) m_autosaver->submit(save::takeSnapshot(m_state)); // a new world is a valid file from the start
}

std::vector<std::string> Session::saveNow() {
    if (!m_autosaver) return {};
    m_autosaver->submit(save::takeSnapshot(m_state));
    return m_autosaver->flush();
}

std::vector<std::string> Session::takeSaveErrors() {
    return m_autosaver ? m_autosaver->takeErrors() : std::vector<std::string>{};
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
    // Autosave on a game-time schedule, the same in the window and headless (a crash test relies on it).
    if (m_autosaver && m_options.autosaveTicks > 0 &&
        m_state.tick % static_cast<std::uint64_t>(m_options.autosaveTicks) == 0) {
        m_autosaver->submit(save::takeSnapshot(m_state));
    }
    return {actions.screenshot, actions.toggleOverlay, actions.toggleHelp, actions.interact};
}

void Session::queue(const std::vector<game::PendulumCommand>& commands) {
    m_commands.pendulum.insert(m_commands.pendulum.end(), commands.begin(), commands.end());
}

void Session::queue(const std::vector<game::HairCommand>& commands) {
    m_commands.hair.insert(m_commands.hair.end(), commands.begin(), commands.end());
}

void Session::writeDump(const std::string& path) const {
    core::AtomicFile out(path); // a failure never leaves a half-written file (or a temporary one) behind
    out.stream() << game::dumpState(m_state).dump(2) << '\n';
    out.commit();
}

} // namespace session
