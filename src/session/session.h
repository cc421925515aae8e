// What the window and the headless runner share: the game state, the input mapper fed by a script and
// by live events through the same path, and one fixed tick. Keeping it in one place is what makes a
// headless run a faithful twin of the windowed game.
#pragma once
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "game/game_state.h"
#include "input/mapper.h"
#include "input/script.h"
#include "session/autosaver.h"
#include "session/keyframe_file.h"
#include "session/keyframes.h"
#include "session/options.h"
#include "session/recording.h"
#include "session/settings.h"

namespace session {

// The parts of a tick's actions that belong to the program rather than the simulation.
struct AppRequests {
    bool screenshot = false;
    bool toggleOverlay = false;
    bool toggleHelp = false;
    bool interact = false;
};

// A seek that cannot be made: the tick named is behind the first keyframe, past a replay's end, or the session
// records; or a keyframe budget that does not hold one keyframe of the replay. The program exits with 2.
class SeekError : public std::runtime_error {
    using runtime_error::runtime_error;
};

class Session {
public:
    // Throws input::ScriptError for a bad script, save::WorldFileError for a world that cannot be read. Every
    // setting (the simulation's, the input's bindings and tuning) is options.settings: the run's settings after
    // mergeSettings.
    explicit Session(const Options& options);
    ~Session();

    // Applies the script lines due at the coming tick, turns pending input into actions, advances one tick.
    AppRequests step();
    // Pauses or resumes at the next tick (the pause menu's buttons, focus loss).
    void requestPauseToggle() { m_pauseToggle = true; }
    // Panel edits, applied at the start of the next tick.
    void queue(const std::vector<game::PendulumCommand>& commands);
    void queue(const std::vector<game::HairCommand>& commands);
    // Sets the time of day at the next tick (the pause menu's slider), as a script's `time` line does; recorded.
    // An hour outside [0, 24) is ignored.
    void queueTimeOfDay(double hours);
    // Puts `item` into hotbar slot `slot` (0-based) at the next tick (the block picker), as a script's `hotbar`
    // line does; recorded. A slot out of range or an item no slot holds is ignored.
    void queueHotbar(int slot, const game::Item& item);

    double tickSeconds() const { return 1.0 / m_options.settings.tickRate; }
    game::GameState& state() { return m_state; }
    const game::GameState& state() const { return m_state; }
    input::InputMapper& mapper() { return m_mapper; }
    // The script's events as parsed at start, sorted by tick (empty without --script).
    const std::vector<input::ScriptEvent>& script() const { return m_script; }
    // The settings panel's live settings, from the next tick: the input's into the mapper, hair detail and budget
    // into the game, the rest into options().settings for the frontend to read. While a recording runs the
    // simulation's keep the values of its header, so it replays: returns the labels of those kept.
    std::vector<std::string> applySettings(const Settings& settings);
    const Options& options() const { return m_options; }

    // A replay (--script naming a recording): the recording's last tick; nullopt otherwise. The replay checks
    // the state hash wherever the recording has one and throws ReplayDiverged at the first that differs.
    std::optional<std::uint64_t> replayEndTick() const {
        return m_replay ? std::optional<std::uint64_t>(m_replay->endTick) : std::nullopt;
    }
    // Keyframes (session/keyframes.h) from now on: one of the state now, then one every `interval` ticks of the
    // state, kept within budgetBytes. Throws std::invalid_argument naming the value for an interval of 0 or a budget
    // that does not hold the first keyframe.
    void keepKeyframes(std::uint64_t interval, std::size_t budgetBytes);
    // A replay's keyframes read from the file beside its recording (session/keyframe_file.h), by tick; seek()
    // restores from them as from the kept ones. Empty without a file, after a take-over, and for a script.
    const std::map<std::uint64_t, FileKeyframe>& fileKeyframes() const { return m_fileKeyframes; }
    // What reading that file warned about (each also logged), and what seek() found (a keyframe whose restored
    // state did not hash as recorded, then left out).
    const std::vector<std::string>& keyframeWarnings() const { return m_keyframeWarnings; }
    const KeyframeStore* keyframes() const { return m_keyframes.get(); }
    // Brings the state to tick `target`: from the nearest keyframe at or before it (kept, from the recording's file,
    // or a replay's start) when the target lies behind the state or that keyframe lies kRestoreAhead ticks or more
    // ahead of it, else by stepping on; a replay's hashes are checked on the way, and screenshots the ticks ask for
    // are not taken. Throws SeekError naming the tick for a target behind the first keyframe (behind the state,
    // without keyframes), past a replay's last tick, or while recording.
    void seek(std::uint64_t target);
    // seek() within about `budgetSeconds` of this thread's CPU: a restore is made at once, the stepping forward stops
    // when the budget is spent (the next call goes on). True once the state is at `target`.
    bool seekToward(std::uint64_t target, double budgetSeconds);
    // What the last seek restored before stepping on: the tick and where it came from ("a kept keyframe", "the
    // keyframe file", "the start world"); nullopt when it only stepped on.
    struct Restore {
        std::uint64_t tick = 0;
        const char* source = "";
    };
    const std::optional<Restore>& lastRestore() const { return m_lastRestore; }
    // The replay's first tick (its start world's); 0 when this is no replay.
    std::uint64_t replayStartTick() const { return m_replay ? m_replay->header.startTick : 0; }
    // Leaves the replay at the state's tick and plays live from exactly that state: the recording's remaining lines
    // are dropped, keys and buttons it held are let go, the keyframes are let go (live play keeps none), and with
    // --record the new recording starts here (its start world this state, as any
    // recording's: a carried ball put down). In the window a replay (--replay) records only from a take-over.
    void takeOver();

    // --record: writes the end line and puts the recording in place (also done by the destructor).
    void finishRecording();

    // Writes the JSON dump to path; throws std::runtime_error naming the path on failure.
    void writeDump(const std::string& path) const;

    // The world file this session plays, if any: opened (or created) at start, autosaved every
    // options.autosaveTicks ticks of game time by a background thread, saved at the end on request.
    bool hasWorld() const { return m_autosaver != nullptr; }
    std::filesystem::path worldPath() const;
    // Plays the recording `file` from now on, as --replay does (the pause menu's Recordings page): the world played
    // so far is saved and let go, a recording being made is finished, and a take-over records nothing (--record named
    // the live session's file). The recording's simulation settings become the session's. Throws what --replay's
    // start throws (input::ScriptError, save::WorldFileError, SeekError), leaving the session as it was.
    void openReplay(const std::filesystem::path& file);
    // Switches to another world file (the pause menu's world list): saves the current one first.
    void openWorld(const std::filesystem::path& file, std::uint64_t seedIfNew, world::TerrainKind terrainIfNew);
    // Saves now and waits; returns what went wrong (empty when saved).
    std::vector<std::string> saveNow();
    // Save problems reported since the last call (autosaves run in the background).
    std::vector<std::string> takeSaveErrors();
    const std::vector<std::string>& loadWarnings() const { return m_loadWarnings; }

private:
    Options m_options;
    game::GameState m_state;
    input::InputMapper m_mapper;
    std::vector<input::ScriptEvent> m_script;
    std::size_t m_next = 0;
    bool m_pauseToggle = false;
    game::TickCommands m_commands;
    std::unique_ptr<Autosaver> m_autosaver;
    std::vector<std::string> m_loadWarnings;
    std::optional<Recording> m_replay;
    std::unique_ptr<Recorder> m_recorder;
    std::unique_ptr<KeyframeStore> m_keyframes;
    std::map<std::uint64_t, FileKeyframe> m_fileKeyframes;
    std::vector<std::string> m_keyframeWarnings;
    std::optional<Restore> m_lastRestore;
    std::shared_ptr<const game::StateImage> m_replayStart; // a replay's start state: where a seek falls back to
    std::unique_ptr<KeyframeFileWriter> m_keyframeFile;    // --record: the keyframes written beside the recording

    void startReplay(const Recording& recording);
    void keepWorldDay(const std::filesystem::path& file);
    void startRecording();
    void queueEdit(const input::EditEvent& edit, int line);
    Keyframe takeKeyframe() const;
    void loadKeyframeFile();
    void checkSeekTarget(std::uint64_t target) const; // throws SeekError as seek() does
    // Restores what a seek to `target` starts from, if it restores (restorePoint): a file keyframe that fails its
    // check is left out with a warning and the next earlier one restored.
    void restoreFor(std::uint64_t target);
    static constexpr std::uint64_t kRestoreAhead = 60; // ticks a keyframe ahead of the state must save
    void checkKeyframeBudget() const;
    // The tick a seek to `target` restores from (a kept keyframe, a file keyframe or the replay's start, the latest at
    // or before it; `target` itself when there is none), if it restores: `force`, the target lies behind the state, or
    // a keyframe lies kRestoreAhead ticks or more ahead of the state.
    std::optional<std::uint64_t> restorePoint(std::uint64_t target, bool force = false) const;
    // The input a replay's tick starts with: the mapper and the next script event after stepping the script's
    // events (not the game) from the replay's start to `tick`.
    std::pair<input::InputMapper, std::size_t> inputAt(std::uint64_t tick) const;
};

} // namespace session
