// Recorded sessions: `minecrappy --record FILE` writes what every tick consumed, in the script format, so
// `minecrappy --headless --script FILE` replays it to the same state. The file is a script with a header:
//
//   # minecrappy recording 3            format (older ones, made before the day clock, are refused)
//   # version 0.1.0                     the game that wrote it (a newer one is refused)
//   # seed 1 / # terrain default        the world's
//   # hair_detail 2 / # hair_budget 1000 / # tick_rate 60 / # day_length 20.0 / # day_cycle true
//                                       the settings that change the simulation (the rows of
//                                       session/setting_table.h marked so), as the settings file writes them
//   # start_world rec.mcscript.start.mcworld   the state the session began from (beside the file; while an
//                                       older recording's is kept, rec.mcscript.start.2.mcworld, ...)
//   # start_tick 0 / # hash_every 10
//   # hash 0 5d0c...                    the start state's game::stateHash
//   0 act move=0,1 sprint               a tick's whole intent (input::ActionsEvent), only ticks that had any
//   0 hair 1 radius=0.4 ...             a panel's edit, applied by that tick (game/command_text.h)
//   # hash 10 9a1f...                   the state after tick 10, every hash_every ticks
//   # end 1234                          the last tick; a file without it was cut short
//
// Recording the actions a tick consumed rather than raw device events (as Doom's demos do) makes the replay
// independent of bindings, sensitivities and frame timing; the state hashes prove it. The start world is the
// whole state (blocks, objects, player), so a session on a long-played world replays from where it began.
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/atomic_file.h"
#include "game/game_state.h"
#include "input/actions.h"
#include "save/world_store.h"
#include "session/settings.h"

namespace session {

inline constexpr int kRecordingFormat = 3;
inline constexpr std::string_view kRecordingMagic = "# minecrappy recording ";
// Ticks between state hashes: a divergence is caught within this many ticks (a sixth of a second at 60 Hz)
// for about 20 bytes a line (1.3 MB an hour).
inline constexpr std::uint64_t kRecordingHashEvery = 10;

struct RecordingHeader {
    int format = kRecordingFormat;
    std::string version;
    std::uint64_t seed = 0;
    std::string terrain;
    Settings settings;      // its simulation rows (session/setting_table.h); the others are not recorded
    std::string startWorld; // file name, in the recording's folder
    std::uint64_t startTick = 0;
    std::uint64_t hashEvery = kRecordingHashEvery;
};

// What a replay checks, read from the recording's comment lines.
struct Recording {
    RecordingHeader header;
    std::map<std::uint64_t, std::uint64_t> hashes; // state tick -> game::stateHash (the start tick: the start state)
    std::uint64_t endTick = 0;
    std::map<std::string, int, std::less<>> headerLines; // a header key -> its line number (for messages)
};

// True when the text starts like a recording (a script written by hand does not).
bool isRecording(std::string_view text);
// Throws input::ScriptError("FILE:LINE: ...") for a header line that is missing, malformed or given twice, a
// hash line that is not one (or a second for its tick), or a file without its end line (cut short).
Recording parseRecording(std::string_view text, std::string_view fileName);
// Compares dotted version numbers ("0.10.2" > "0.9.9"): negative, zero or positive.
int compareVersions(std::string_view a, std::string_view b);

// A replay reached a state other than the recorded one: the process exits with 3.
class ReplayDiverged : public std::runtime_error {
public:
    ReplayDiverged(std::uint64_t tick, const std::string& message) : std::runtime_error(message), m_tick(tick) {}
    std::uint64_t tick() const { return m_tick; }

private:
    std::uint64_t m_tick;
};

class Recorder {
public:
    // Writes the start world at once, beside the file `path` leads to (FILE.start.mcworld, or FILE.start.N.mcworld
    // while an older one of that name is still held), and opens the recording; the recording file appears,
    // complete, at finish() (written beside it and renamed), and only then is the start world of the recording it
    // replaced removed. Throws core::OutputError naming the file when either cannot be written, or when `path`
    // leads to a pipe or a device (a recording needs a folder for its start world).
    Recorder(const std::filesystem::path& path, RecordingHeader header, const save::Snapshot& start,
             std::uint64_t startHash);
    // Before tick `tick` runs: its actions (nothing is written for a default Actions) and panel edits.
    void beforeTick(std::uint64_t tick, const input::Actions& actions, const game::TickCommands& commands);
    // After a tick: the state's tick and hash, written every hash_every ticks.
    void afterTick(std::uint64_t tick, std::uint64_t hash);
    // Whether afterTick writes the hash of this tick (so a caller hashes only then).
    bool writesHashAt(std::uint64_t tick) const { return !m_finished && tick % m_hashEvery == 0; }
    // Writes the end line and puts the file in place, then removes the replaced recording's start world. Throws
    // core::OutputError when the file cannot be written, having removed this recording's start world (the old
    // recording and its start world are left as they were). Later calls do nothing.
    void finish(std::uint64_t endTick);
    bool finished() const { return m_finished; }
    std::uint64_t startTick() const { return m_startTick; }
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
    std::filesystem::path m_startWorld;    // this recording's, beside the file the path leads to
    std::filesystem::path m_oldStartWorld; // the one the recording at the path named, removed once it is replaced
    std::optional<core::AtomicFile> m_out;
    std::uint64_t m_hashEvery;
    std::uint64_t m_startTick;
    bool m_finished = false;
};

} // namespace session
