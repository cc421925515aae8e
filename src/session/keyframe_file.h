// A recording's keyframes on disk: FILE.keys beside the recording FILE (beside the file its path leads to, as
// its start world), so that a headless `--seek TICK` restores the nearest keyframe at or before TICK and steps
// only from there, instead of replaying from the start world.
//
// The file (little-endian, the machine's float layout, as the world file's hair blob):
//   "MCKEYS2\n", u64 start tick (the recording's), u64 interval (ticks between keyframes)
//   then per keyframe, in tick order: u64 tick, u64 state hash (game::stateHash of the state it holds), u64 length,
//   u64 checksum (FNV-1a of the payload), the payload: the game::StateImage (encodeStateImage below).
// A keyframe's tick is a multiple of the interval, itself a multiple of the recording's hash_every, so the
// recording holds the hash of every keyframe's tick: a keyframe whose hash is not the recording's belongs to another
// recording (a stale file) and is not used. A ball that has not changed since the previous keyframe (asleep,
// most of the time) is written as a reference to it, so the file grows with what moves, not with what exists.
//
// Reading checks each keyframe's checksum and its hash against the recording's; the session checks the restored
// state's hash again. A damaged keyframe (and any referring to a ball in it) is left out with a warning, and a
// seek goes from an earlier one: a keyframe file is a cache, and the recording alone always replays.
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "game/state_image.h"

namespace session {

struct Recording;

inline constexpr std::string_view kKeyframeFileMagic = "MCKEYS2\n"; // 1: before the evaluation counts

// `recording` with ".keys" appended, beside the file the path leads to.
std::filesystem::path keyframeFilePath(const std::filesystem::path& recording);

// Collects keyframes while a session records and writes them beside the recording at the end.
class KeyframeFileWriter {
public:
    // interval: a multiple of hashEvery (the caller rounds it up).
    KeyframeFileWriter(std::uint64_t startTick, std::uint64_t interval);
    bool wants(std::uint64_t tick) const { return tick > m_startTick && tick % m_interval == 0; }
    // The state after tick image.tick, hashing to stateHash; encoded now (sharing what the previous one holds).
    void add(const game::GameState& state, std::uint64_t stateHash);
    // Writes the file atomically (core::AtomicFile); throws core::OutputError naming it. With no keyframe (a
    // recording shorter than one interval) nothing is written and a stale file at `path` is removed.
    void write(const std::filesystem::path& path) const;
    std::size_t size() const { return m_count; }
    std::size_t bytes() const { return m_bytes.size(); }

private:
    std::uint64_t m_startTick, m_interval;
    std::string m_bytes; // the keyframes' part of the file
    std::size_t m_count = 0;
    std::unique_ptr<game::StateImage> m_previous; // the last keyframe's image, to share its balls
};

struct FileKeyframe {
    game::StateImage image; // its def is the session's (a replay's settings are its recording's)
    std::uint64_t hash = 0; // the recording's hash at its tick
};

struct KeyframeFileLoad {
    std::map<std::uint64_t, FileKeyframe> frames; // by tick
    std::uint64_t interval = 0;
    std::vector<std::string> warnings; // "FILE: the keyframe at tick T is damaged (...): ..." one each
};

// Reads the keyframes of `recording` from `path`; `def` is the replay's GameDef. A missing file gives nothing and no
// warning; a file that is not one, or of another recording, one warning; a damaged keyframe one each. Never
// throws for the file's content (std::bad_alloc aside).
KeyframeFileLoad readKeyframeFile(const std::filesystem::path& path, const Recording& recording,
                                  const game::GameDef& def);

} // namespace session
