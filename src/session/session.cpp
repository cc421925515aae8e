#include "session/session.h"

#include "core/atomic_file.h"
#include "core/log.h"
#include "core/thread_clock.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "game/command_text.h"
#include "game/state_io.h"
#include "input/script.h"
#include "session/setting_table.h"

namespace session {

namespace {
// What the simulation settings (the rows marked so in session/setting_table.h, but the tick rate, which is the
// clock's) set in the game.
void setSimulation(game::GameDef& def, const Settings& settings) {
    def.hairDetail = hairDetailFraction(settings.hairDetail);
    def.hairBudget = hairBudgetPasses(settings);
    def.day.dayMinutes = static_cast<double>(settings.dayLengthMinutes);
    def.day.stopped = !settings.dayCycle;
}
// The day's length and whether it runs are the settings'; its hour is the world's own.
void setSimulation(game::GameState& state, const Settings& settings) {
    setSimulation(state.def, settings);
    state.day.dayMinutes = state.def.day.dayMinutes;
    state.day.stopped = state.def.day.stopped;
}

game::GameDef gameDef(const Options& o, const Settings& settings) {
    game::GameDef def;
    setSimulation(def, settings);
    def.terrain.seed = o.seed;
    def.terrain.kind = o.terrain;
    def.day.hours = o.timeOfDay.value_or(game::kDefaultHours);
    return def;
}
} // namespace

Session::Session(const Options& options)
    : m_options(options), m_state(gameDef(options, options.settings)), m_mapper(options.settings.input) {
    if (!options.script.empty()) {
        const std::string text = input::readScriptText(options.script);
        // A recording's header first: a file cut short mid-line is reported as cut short, not as a bad line.
        std::optional<Recording> recording;
        if (isRecording(text)) recording = parseRecording(text, options.script);
        if (options.replay && !recording)
            throw input::ScriptError(
                options.script + ": not a recording (--replay plays what --record wrote; run a script with --script)");
        m_script = input::parseScript(text, options.script);
        // Every panel edit is read once now, so a bad one stops the run before its first tick.
        for (const auto& e : m_script) {
            if (e.edit) {
                queueEdit(*e.edit, e.line);
                m_commands = {};
            }
        }
        if (recording) {
            startReplay(*recording);
            loadKeyframeFile();
            checkKeyframeBudget();
        }
    }
    if (!options.world.empty() && !m_replay) openWorld(options.world, options.seed, options.terrain);
    if (options.timeOfDay) m_state.day.hours = *options.timeOfDay; // a loaded world's (gameDef gave a new one its)
    // A script's ticks are the world's own: in a world saved at tick 300, an event at tick 8 would have fired
    // long ago. Refused before the first tick rather than fired all at once.
    for (const auto& e : m_script) {
        if (e.tick < m_state.tick)
            throw input::ScriptError(m_options.script + ":" + std::to_string(e.line) + ": tick " +
                                     std::to_string(e.tick) + " is before the world's tick " +
                                     std::to_string(m_state.tick) +
                                     " (a script's ticks count from the world's own; docs/SCRIPTS.md)");
    }
    // A replay in the window is a timeline: it records only from a take-over (takeOver()).
    if (!options.record.empty() && !(options.replay && !options.headless)) startRecording();
}

void Session::queueEdit(const input::EditEvent& edit, int line) {
    try {
        if (edit.object == "time") {
            m_commands.timeOfDay = game::parseHours(edit.words.at(0));
        } else if (edit.object == "hotbar") {
            m_commands.hotbar.push_back(game::hotbarCommandFrom(edit.index, edit.words.at(0)));
        } else if (edit.object == "pendulum") {
            m_commands.pendulum.push_back(game::pendulumCommandFrom(edit.index, edit.words));
        } else {
            m_commands.hair.push_back(game::hairCommandFrom(edit.index, edit.words));
        }
    } catch (const std::invalid_argument& e) {
        throw input::ScriptError(m_options.script + ":" + std::to_string(line) + ": " + edit.object + ": " + e.what());
    }
}

void Session::startReplay(const Recording& r) {
    const std::string& file = m_options.script;
    const auto refuse = [&](const std::string& why) { throw input::ScriptError(file + ": " + why); };
    if (compareVersions(r.header.version, MC_VERSION) > 0)
        refuse("recorded by Minecrappy " + r.header.version + ", newer than this game (" + MC_VERSION + ")");
    // The settings that change the simulation come from the recording; one asked for with another value is refused.
    for (std::size_t i = 0; i < kSettingRows.size(); ++i) {
        const SettingRow& row = kSettingRows[i];
        if (!row.simulation) continue;
        if (m_options.given.settings[i] && !sameSetting(row, m_options.settings, r.header.settings))
            refuse("recorded with " + std::string(row.key) + " " + settingText(row, r.header.settings) +
                   "; this run asks for " + std::string(row.flag) + " " + settingText(row, m_options.settings) +
                   " (leave it out to replay)");
        copySetting(row, r.header.settings, m_options.settings);
    }
    if (m_options.timeOfDay) refuse("a replay starts at its start world's time of day; leave out --time-of-day");
    if (!m_options.world.empty())
        refuse("a replay starts from the recording's own start world (" + r.header.startWorld + "); leave out --world");
    // The world's seed and terrain come from the recording too: a different one asked for is refused, not
    // ignored.
    if (m_options.given.seed && m_options.seed != r.header.seed)
        refuse("recorded with seed " + std::to_string(r.header.seed) + "; this run asks for --seed " +
               std::to_string(m_options.seed) + " (leave it out to replay)");
    if (m_options.given.terrain && std::string(world::terrainName(m_options.terrain)) != r.header.terrain)
        refuse("recorded on terrain " + r.header.terrain + "; this run asks for --terrain " +
               std::string(world::terrainName(m_options.terrain)) + " (leave it out to replay)");
    // The start world lies beside the file the path leads to (a recording replayed through a link finds it).
    std::error_code ec;
    std::filesystem::path real = std::filesystem::canonical(file, ec);
    if (ec) real = file;
    const std::filesystem::path startPath = real.parent_path() / r.header.startWorld;
    const std::string image = input::readScriptText(startPath.string()); // bounded read, same errors
    auto store = save::WorldStore::openImage(
        std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(image.data()), image.size()),
        startPath.string());
    if (store->isNew()) refuse(startPath.string() + " holds no saved state");
    game::GameState start = save::restore(store->load());
    const game::DayClock worldDay = start.day; // the day as saved (the recorder saved the session's)
    setSimulation(start, m_options.settings);
    const std::string terrain(world::terrainName(start.def.terrain.kind));
    if (start.def.terrain.seed != r.header.seed || terrain != r.header.terrain || start.tick != r.header.startTick)
        refuse("its header (seed " + std::to_string(r.header.seed) + ", terrain " + r.header.terrain + ", tick " +
               std::to_string(r.header.startTick) + ") does not match its start world " + startPath.string() +
               " (seed " + std::to_string(start.def.terrain.seed) + ", terrain " + terrain + ", tick " +
               std::to_string(start.tick) + ")");
    if (game::stateHash(start) != r.hashes.at(r.header.startTick)) {
        // The start world holds the day the session ran, as the header does: a day line that disagrees with the
        // world while the world alone gives the recorded hash was edited; name it.
        const game::DayClock headerDay = start.day;
        start.day.dayMinutes = worldDay.dayMinutes; // the refusal below throws: `start` is not used after it
        start.day.stopped = worldDay.stopped;
        if (game::stateHash(start) == r.hashes.at(r.header.startTick)) {
            const auto lineOf = [&](const char* key) { return std::to_string(r.headerLines.at(key)); };
            const std::string world = startPath.string();
            if (worldDay.dayMinutes != headerDay.dayMinutes)
                throw input::ScriptError(file + ":" + lineOf("day_length") + ": '# day_length " +
                                         settingFloatText(m_options.settings.dayLengthMinutes) +
                                         "' is not the day length of its start world " + world + " (" +
                                         settingFloatText(static_cast<float>(worldDay.dayMinutes)) +
                                         ", which its start hash agrees with): the header was edited");
            throw input::ScriptError(file + ":" + lineOf("day_cycle") + ": '# day_cycle " +
                                     (m_options.settings.dayCycle ? "true" : "false") +
                                     "' is not what its start world " + world + " holds (" +
                                     (worldDay.stopped ? "false" : "true") +
                                     ", which its start hash agrees with): the header was edited");
        }
        refuse("its start world " + startPath.string() + " is not the state it was recorded from (state hash differs)");
    }
    m_state = std::move(start);
    m_replay = r;
    m_replayStart = std::make_shared<const game::StateImage>(game::takeImage(m_state));
}

void Session::loadKeyframeFile() {
    KeyframeFileLoad load = readKeyframeFile(keyframeFilePath(m_options.script), *m_replay, m_state.def);
    for (const std::string& w : load.warnings) core::logWarn("%s", w.c_str());
    m_keyframeWarnings = std::move(load.warnings);
    m_fileKeyframes = std::move(load.frames);
}

void Session::checkKeyframeBudget() const {
    // Headless a replay keeps no keyframes, but its budget is checked alike: the same run in the window would be
    // refused.
    {
        const std::size_t budget = std::size_t(m_options.settings.keyframeBudgetMiB) << 20;
        KeyframeStore probe(1, std::numeric_limits<std::size_t>::max());
        probe.add({game::takeImage(m_state), m_mapper, m_next});
        if (probe.bytes() > budget) {
            char need[32];
            std::snprintf(need, sizeof need, "%.1f", static_cast<double>(probe.bytes()) / (1 << 20));
            throw SeekError("--keyframe-budget " + std::to_string(m_options.settings.keyframeBudgetMiB) +
                            ": one keyframe of " + m_options.script + " takes " + need + " MiB");
        }
    }
}

void Session::startRecording() {
    // Both the session and the file start from the same restored snapshot, so the replay has nothing the
    // recording lacked (hair strands start from their spawn pose in both, as after any load).
    const save::Snapshot snapshot = save::takeSnapshot(m_state);
    m_state = save::restore(snapshot);
    setSimulation(m_state, m_options.settings);
    RecordingHeader h;
    h.version = MC_VERSION;
    h.seed = m_state.def.terrain.seed;
    h.terrain = std::string(world::terrainName(m_state.def.terrain.kind));
    h.settings = m_options.settings;
    h.startTick = m_state.tick;
    h.hashEvery = kRecordingHashEvery;
    m_recorder = std::make_unique<Recorder>(m_options.record, h, snapshot, game::stateHash(m_state));
    const std::uint64_t every = h.hashEvery,
                        asked = static_cast<std::uint64_t>(m_options.settings.keyframeFileInterval);
    m_keyframeFile = std::make_unique<KeyframeFileWriter>(m_state.tick, (asked + every - 1) / every * every);
}

void Session::finishRecording() {
    if (!m_recorder || m_recorder->finished()) return;
    m_recorder->finish(m_state.tick);
    core::logNote("recorded %s (ticks %llu to %llu)", m_recorder->path().c_str(),
                  static_cast<unsigned long long>(m_recorder->startTick()),
                  static_cast<unsigned long long>(m_state.tick));
    // The keyframes after the recording: a kill in between leaves the recording without them (or with an older
    // recording's, which a replay tells by their hashes), never a recording that does not replay.
    if (m_keyframeFile) {
        const std::filesystem::path keys = keyframeFilePath(m_recorder->path());
        try {
            m_keyframeFile->write(keys);
            if (m_keyframeFile->size() > 0)
                core::logNote("wrote %zu keyframes (%.1f MiB) to %s", m_keyframeFile->size(),
                              static_cast<double>(m_keyframeFile->bytes()) / (1 << 20), keys.c_str());
        } catch (const std::exception& e) {
            core::logError("%s (the recording is kept; a seek in it replays from its start)", e.what());
        }
        m_keyframeFile.reset();
    }
}

Session::~Session() {
    try {
        finishRecording();
    } catch (const std::exception& e) {
        core::logError("%s", e.what());
    }
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
    // A recording cannot follow a switch of worlds: it ends where the old world was left.
    if (m_recorder && !m_recorder->finished()) finishRecording();
    // Settings of this machine, not of the world; the day is the world's (below).
    if (loaded) {
        m_state = std::move(*loaded);
        keepWorldDay(file);
    } else {
        Options o = m_options;
        o.seed = seedIfNew;
        o.terrain = terrainIfNew;
        m_state = game::GameState(gameDef(o, m_options.settings));
    }
    m_loadWarnings = std::move(warnings);
    m_autosaver = std::make_unique<Autosaver>(std::move(store));
    if (!loaded) m_autosaver->submit(save::takeSnapshot(m_state)); // a new world is a valid file from the start
}

void Session::openReplay(const std::filesystem::path& file) {
    // The replay is started in a session of its own first: a bad recording throws before anything here changes.
    Options o = m_options;
    o.script = file.string();
    o.replay = true;
    o.world.clear();
    o.record.clear();
    o.seek.reset();
    o.timeOfDay.reset();
    o.given = {}; // the command line's flags were this session's: none of them asks the recording for anything
    Session next(o);
    // The world played so far is saved before it is let go; a save that fails stops the switch here.
    if (m_autosaver) {
        const std::vector<std::string> errors = saveNow();
        if (!errors.empty()) throw std::runtime_error("the world could not be saved, so it is kept: " + errors.front());
    }
    m_autosaver.reset();
    // The recording being made ends here; one that cannot be written is reported, and the switch goes on (the
    // older recording at its path is kept, as when the game ends).
    try {
        if (m_recorder && !m_recorder->finished()) finishRecording();
    } catch (const std::exception& e) {
        core::logError("%s", e.what());
    }
    m_recorder.reset();
    m_keyframeFile.reset();
    m_keyframes.reset();
    m_options.script = o.script;
    m_options.replay = true;
    m_options.record.clear();
    m_options.given = o.given; // the recording's settings are not the command line's
    m_options.settings = next.m_options.settings;
    m_state = std::move(next.m_state);
    m_mapper = next.m_mapper;
    m_script = std::move(next.m_script);
    m_next = 0;
    m_pauseToggle = false;
    m_commands = {};
    m_replay = std::move(next.m_replay);
    m_replayStart = std::move(next.m_replayStart);
    m_fileKeyframes = std::move(next.m_fileKeyframes);
    m_keyframeWarnings = std::move(next.m_keyframeWarnings);
    m_lastRestore.reset();
    m_loadWarnings.clear();
}

void Session::keepWorldDay(const std::filesystem::path& file) {
    // The day's length and whether it runs are the world's, saved with it: they become this session's settings
    // (so the panel, a recording's header and the next save agree with the world), unless the command line gave
    // --day-length or --day-cycle, which win for this session and are named.
    const game::DayClock world = m_state.day;
    Settings& s = m_options.settings;
    const bool lengthGiven = m_options.given.setting("day_length"), cycleGiven = m_options.given.setting("day_cycle");
    if (lengthGiven && static_cast<double>(s.dayLengthMinutes) != world.dayMinutes) {
        core::logNote("%s: its day of %g minutes is %g minutes in this session (--day-length)", file.c_str(),
                      world.dayMinutes, static_cast<double>(s.dayLengthMinutes));
    }
    if (cycleGiven && s.dayCycle == world.stopped) {
        core::logNote("%s: its time %s in this session (--day-cycle %s)", file.c_str(),
                      s.dayCycle ? "stood still; it passes" : "passed; it stands still", s.dayCycle ? "true" : "false");
    }
    if (!lengthGiven) s.dayLengthMinutes = static_cast<float>(world.dayMinutes);
    if (!cycleGiven) s.dayCycle = !world.stopped;
    setSimulation(m_state, s);
    if (!lengthGiven) m_state.def.day.dayMinutes = m_state.day.dayMinutes = world.dayMinutes; // exactly the file's
}

std::vector<std::string> Session::applySettings(const Settings& settings) {
    std::vector<std::string> kept;
    for (const SettingRow& row : kSettingRows) {
        if (!row.live || sameSetting(row, settings, m_options.settings)) continue;
        // A recording holds the simulation settings it started with (its header): a change would not replay.
        if (row.simulation && m_recorder && !m_recorder->finished()) {
            kept.emplace_back(row.label);
            continue;
        }
        copySetting(row, settings, m_options.settings);
    }
    m_options.settings.input = settings.input; // the bindings, which are not rows, and the tuning rows again
    m_mapper.config() = m_options.settings.input;
    setSimulation(m_state, m_options.settings);
    return kept;
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
        const input::ScriptEvent& e = m_script[m_next];
        if (e.edit) {
            queueEdit(*e.edit, e.line);
        } else {
            m_mapper.handle(e.event);
        }
        ++m_next;
    }
    input::Actions actions = m_mapper.takeTickActions(static_cast<float>(tickSeconds()));
    if (m_pauseToggle) {
        actions.togglePause = !actions.togglePause;
        m_pauseToggle = false;
    }
    if (m_recorder) m_recorder->beforeTick(m_state.tick, actions, m_commands);
    game::tick(m_state, actions, tickSeconds(), m_commands);
    m_commands = {};
    // Hashed only on the ticks a recording writes or a replay checks: the hash reads every hair node.
    if (m_recorder && m_recorder->writesHashAt(m_state.tick)) {
        const std::uint64_t hash = game::stateHash(m_state);
        m_recorder->afterTick(m_state.tick, hash);
        if (m_keyframeFile && m_keyframeFile->wants(m_state.tick)) m_keyframeFile->add(m_state, hash);
    }
    if (m_replay) {
        if (const auto it = m_replay->hashes.find(m_state.tick); it != m_replay->hashes.end()) {
            if (const std::uint64_t hash = game::stateHash(m_state); hash != it->second) {
                char text[160];
                std::snprintf(text, sizeof text, "state hash %016llx at tick %llu, recorded %016llx",
                              static_cast<unsigned long long>(hash), static_cast<unsigned long long>(m_state.tick),
                              static_cast<unsigned long long>(it->second));
                throw ReplayDiverged(m_state.tick, m_options.script + ": the replay left the recording: " + text);
            }
        }
    }
    if (m_keyframes && m_keyframes->wants(m_state.tick)) m_keyframes->add(takeKeyframe());
    // Autosave on a game-time schedule, the same in the window and headless (a crash test relies on it).
    if (m_autosaver && m_options.autosaveTicks > 0 &&
        m_state.tick % static_cast<std::uint64_t>(m_options.autosaveTicks) == 0) {
        m_autosaver->submit(save::takeSnapshot(m_state));
    }
    return {actions.screenshot, actions.toggleOverlay, actions.toggleHelp, actions.interact};
}

Keyframe Session::takeKeyframe() const {
    const Keyframe* before = m_keyframes->atOrBelow(m_state.tick);
    return {game::takeImage(m_state, before ? &before->state : nullptr), m_mapper, m_next};
}

void Session::keepKeyframes(std::uint64_t interval, std::size_t budgetBytes) {
    auto store = std::make_unique<KeyframeStore>(interval, budgetBytes);
    m_keyframes = std::move(store);
    m_keyframes->add(takeKeyframe());
    if (m_keyframes->bytes() > budgetBytes) {
        const std::size_t needs = m_keyframes->bytes();
        m_keyframes.reset();
        throw std::invalid_argument("a keyframe budget of " + std::to_string(budgetBytes) +
                                    " bytes does not hold one keyframe of this session (" + std::to_string(needs) +
                                    " bytes)");
    }
}

std::pair<input::InputMapper, std::size_t> Session::inputAt(std::uint64_t tick) const {
    input::InputMapper mapper(m_options.settings.input);
    std::size_t next = 0;
    for (std::uint64_t t = replayStartTick(); t < tick; ++t) { // step()'s input half
        for (; next < m_script.size() && m_script[next].tick <= t; ++next) {
            if (!m_script[next].edit) mapper.handle(m_script[next].event);
        }
        (void)mapper.takeTickActions(static_cast<float>(tickSeconds()));
    }
    return {mapper, next};
}

std::optional<std::uint64_t> Session::restorePoint(std::uint64_t target, bool force) const {
    std::optional<std::uint64_t> best;
    if (m_replayStart && target >= m_replayStart->tick) best = m_replayStart->tick;
    if (const Keyframe* k = m_keyframes ? m_keyframes->atOrBelow(target) : nullptr;
        k && (!best || k->state.tick > *best))
        best = k->state.tick;
    if (auto it = m_fileKeyframes.upper_bound(target); it != m_fileKeyframes.begin()) {
        const std::uint64_t tick = std::prev(it)->first;
        if (!best || tick > *best) best = tick;
    }
    // A keyframe ahead of the state is worth restoring only when it saves some stepping (a restore costs about what
    // a few dozen ticks do); until then the replay steps on, its hashes checked.
    if (force || target < m_state.tick || (best && *best >= m_state.tick + kRestoreAhead))
        return best ? best : std::optional(target);
    return std::nullopt;
}

void Session::checkSeekTarget(std::uint64_t target) const {
    if (m_recorder && !m_recorder->finished()) throw SeekError("a session that records cannot seek");
    if (m_replay && target > m_replay->endTick)
        throw SeekError("tick " + std::to_string(target) + " is past the last tick of " + m_options.script + ", " +
                        std::to_string(m_replay->endTick));
}

void Session::restoreFor(std::uint64_t target) {
    m_lastRestore.reset();
    for (bool mustRestore = false;;) { // after a file keyframe that failed, an earlier one (the start never fails)
        const std::optional<std::uint64_t> from = restorePoint(target, mustRestore);
        if (!from) return;
        const Keyframe* k = m_keyframes ? m_keyframes->atOrBelow(target) : nullptr;
        const auto file = m_fileKeyframes.find(*from);
        if (k && k->state.tick == *from) {
            game::restoreImage(m_state, k->state);
            m_mapper = k->mapper;
            m_next = k->scriptNext;
            m_lastRestore = {*from, "a kept keyframe"};
        } else if (file != m_fileKeyframes.end()) {
            std::string problem;
            try {
                game::restoreImage(m_state, file->second.image);
                if (game::stateHash(m_state) != file->second.hash) problem = "its state does not hash as recorded";
            } catch (const std::invalid_argument& e) {
                problem = e.what();
            }
            if (!problem.empty()) {
                m_keyframeWarnings.push_back(keyframeFilePath(m_options.script).string() + ": the keyframe at tick " +
                                             std::to_string(*from) + " cannot be restored (" + problem +
                                             "): left out; the seek goes from an earlier one");
                core::logWarn("%s", m_keyframeWarnings.back().c_str());
                m_fileKeyframes.erase(file);
                mustRestore = true;
                continue;
            }
            std::tie(m_mapper, m_next) = inputAt(*from);
            m_lastRestore = {*from, "the keyframe file"};
        } else if (m_replayStart && *from == m_replayStart->tick) {
            game::restoreImage(m_state, *m_replayStart); // the image startReplay took of the checked start state
            std::tie(m_mapper, m_next) = inputAt(*from);
            m_lastRestore = {*from, "the start world"};
        } else {
            const std::string first =
                m_keyframes ? "its first keyframe is at tick " + std::to_string(m_keyframes->frames().begin()->first)
                            : "it keeps no keyframes";
            throw SeekError("tick " + std::to_string(target) + " is behind this session's state (tick " +
                            std::to_string(m_state.tick) + ") and " + first);
        }
        m_mapper.config() = m_options.settings.input;
        m_commands = {};
        m_pauseToggle = false;
        return;
    }
}

void Session::seek(std::uint64_t target) {
    checkSeekTarget(target);
    restoreFor(target);
    while (m_state.tick < target) step();
}

bool Session::seekToward(std::uint64_t target, double budgetSeconds) {
    checkSeekTarget(target);
    restoreFor(target);
    // The restore and the first step are made whatever the budget.
    const double until = core::threadCpuSeconds() + budgetSeconds;
    if (m_state.tick < target) step();
    while (m_state.tick < target && core::threadCpuSeconds() < until) step();
    return m_state.tick == target;
}

void Session::takeOver() {
    if (!m_replay) return;
    m_replay.reset();
    m_script.resize(m_next);
    m_mapper.releaseAll();
    m_keyframes.reset(); // the timeline is gone: live play keeps none (their memory, up to the budget, is let go)
    m_fileKeyframes.clear();
    m_replayStart.reset();
    if (!m_options.record.empty() && !m_recorder) startRecording();
}

void Session::queue(const std::vector<game::PendulumCommand>& commands) {
    m_commands.pendulum.insert(m_commands.pendulum.end(), commands.begin(), commands.end());
}

void Session::queueTimeOfDay(double hours) {
    if (game::isClockHour(hours)) m_commands.timeOfDay = hours;
}

void Session::queueHotbar(int slot, const game::Item& item) {
    if (slot >= 0 && slot < game::kHotbarSize && game::isHoldable(item)) m_commands.hotbar.push_back({slot, item});
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
