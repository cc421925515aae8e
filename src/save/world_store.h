// World saving: one world is one SQLite database holding the terrain seed and kind, the block edits per
// chunk, every pendulum set (with the full integrator state, so a loaded world resumes bit for bit), every
// hair ball (its definition, solver included, pose and hair, so that it too resumes bit for bit), the player and
// the tick.
//
// What it must never do: write to a file it could not read and validate completely, leave a half-written
// save behind, or touch GL. Every save is one transaction in SQLite's rollback journal (journal_mode=DELETE)
// with synchronous=FULL: a SIGKILL or power cut at any moment leaves the file at the last completed save
// (or, at worst, the one before), and the next open rolls an interrupted save back (see open()).
//
// Threads: save() touches only the Snapshot it is given and a connection of its own, opened for that save,
// so the game may call it from one background thread while the main thread keeps running.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "game/game_state.h"
#include "game/space.h"
#include "game/state_fields.h"

struct sqlite3;

namespace save {

// "FILE: what is wrong". The game reports it and exits with code 2; the file is left as it was.
class WorldFileError : public std::runtime_error {
    using runtime_error::runtime_error;
};

// v1: everything but hair balls (the first schema); v2 adds the hair_balls table; v3 adds each hair ball's
// solver (hair_balls.solver, physics::hairMethodName: "ftl", "dftl", ...); v4 each ball's hair (hair_state:
// every node and what the solver carries to its next step), so a loaded world continues bit for bit; v5 the day
// clock (meta time_of_day, day_length, day_stopped; an older file opens at game::kDefaultHours) and the lamp
// block, which a v4 build never sees: it refuses the v5 file whole; v6 whether each ball's sphere is a collider
// for its hair (hair_balls.host_collision; an older file's balls all were); v7 the coloured lamps (block ids 13
// to 17 in chunk_edits), which a v6 build never sees: it refuses the v7 file whole, and in an older file those
// ids are out of range (blockIdsOfSchema). A ball of an older file, or with a hair_state that does not fit it,
// keeps everything else and its hair starts anew (the load warns). The version lives in PRAGMA
// user_version; a file from a newer version is refused, never altered. An older file loads as it is (its balls
// get "dftl", the only solver before v3) and becomes the current version at its next save, in the save's
// transaction. A hair ball whose solver this build does not know (a file from a newer build that added one) is
// not skipped like other bad records: the whole load is refused (WorldFileError naming the file, table, row and
// name), so the file, ball included, is never overwritten by a save without it.
inline constexpr int kSchemaVersion = 7;
// The block ids (world::BlockType values) a chunk_edits blob of a file of schema `version` may hold: 0 to the
// result less one. A lamp in a v4 file, or a coloured lamp in a v6 one, is no block that file's build knew.
int blockIdsOfSchema(int version);
// PRAGMA application_id of every Minecrappy world ("MCWD"), so any other SQLite file is "not a world".
inline constexpr std::int32_t kApplicationId = 0x4D435744;
// Hair nodes (strands x nodes per strand) one saved ball may ask for: the panel's largest ball is 8192 x 32
// = 262144; a file asking for more (up to physics' own limit of 2^26) would allocate gigabytes on load.
inline constexpr std::int64_t kMaxSavedHairNodes = std::int64_t{1} << 20;

// The schema as each version created it (tables only; the pragmas are set by the code): v1's, then what each
// later version adds (also the migration to it). Public so that tests can build an older file and watch it
// migrate.
extern const char* const kSchemaV1Sql;
extern const char* const kSchemaV2Sql;
extern const char* const kSchemaV3Sql;
extern const char* const kSchemaV4Sql;
extern const char* const kSchemaV5Sql;
extern const char* const kSchemaV6Sql;
extern const char* const kSchemaV7Sql;

using PendulumSetRecord = game::PendulumSetRecord;
using HairBallRecord = game::HairBallRecord;

// The hair_state blob of a ball of strands x nodesPerStrand nodes (format in world_store.cpp); decode throws
// std::invalid_argument (saying what) for a blob that is not one, or is of another size.
std::vector<unsigned char> encodeHairState(const physics::HairSolverState& state, int strands, int nodesPerStrand);
physics::HairSolverState decodeHairState(std::span<const unsigned char> blob, int strands, int nodesPerStrand);

// A plain copy of everything saved, cheap to take on the main thread.
struct Snapshot {
    world::TerrainDef terrain{};
    std::uint64_t tick = 0;
    bool paused = false;
    game::DayClock day{}; // a file of schema 4 or older has none: game::kDefaultHours, the default day
    game::Player player{};
    // The saved player could not be trusted (load() warned): restore() puts a new player at the spawn point.
    bool resetPlayer = false;
    std::vector<world::BlockEdit> edits;
    std::vector<PendulumSetRecord> pendulumSets;
    std::vector<HairBallRecord> hairBalls; // a carried ball is saved as put down where it is carried
    // game::stateHash of restore(*this), written with each save as meta 'state_hash' (hex) so a crash test
    // can check that the file holds exactly one complete save. load() fills it from the file.
    std::uint64_t stateHash = 0;
    // Saves this file has completed (meta 'save_count'); load() fills it, save() writes it + 1.
    std::uint64_t saveCount = 0;
};

// Every field of a snapshot, record by record in game/state_fields.h's lists: the world's values (meta), the
// player, each pendulum set and then its four slots, each hair ball. For
// tests that change or compare every field; the writer and reader walk the same lists table by table.
template <class V>
void visitSnapshotFields(Snapshot& s, V& v) {
    game::StateMeta meta{s.tick, s.terrain.seed, s.terrain.kind, s.paused, s.day};
    game::visitMeta(v, meta);
    s.tick = meta.tick, s.terrain.seed = meta.seed, s.terrain.kind = meta.terrain, s.paused = meta.paused,
    s.day = meta.day;
    game::visitPlayer(v, s.player);
    for (auto& r : s.pendulumSets) {
        game::visitPendulumSet(v, r);
        for (std::size_t k = 0; k < game::kPendulumSlots; ++k) game::visitPendulumSlot(v, r, k);
    }
    for (auto& r : s.hairBalls) game::visitHairBall(v, r, r.hair);
}

// The columns a table holds for its field list ("meta": its keys), in the list's order, and the key columns
// before them ("id"; "set_id", "slot"). WorldFile.EveryListedFieldIsAColumn holds them to the schema.
std::vector<std::string> listedColumns(const std::string& table);
std::vector<std::string> keyColumns(const std::string& table);

Snapshot takeSnapshot(const game::GameState& state);
// A GameState with demoObjects = false and then the snapshot's sets, balls, player, edits, tick and pause.
// The player's previous pose equals the current one; no ball is carried.
game::GameState restore(const Snapshot& snapshot);

// Deletes a world file and what SQLite may have left beside it (its rollback journal, or a WAL and its
// shared-memory file from another tool). A missing file is not an error; ec holds the first failure.
void removeWorldFiles(const std::filesystem::path& file, std::error_code& ec);

class WorldStore {
public:
    // An existing file is validated read-only first (header, application id, schema version, quick_check,
    // then every table, value by value) and throws WorldFileError if it cannot be trusted. Only a file that
    // passed is ever opened for writing. Exception: a hot journal left by a save that was killed is rolled
    // back by SQLite before validation (that is the crash recovery; it restores the last completed save),
    // and only if the file's header says it is a Minecrappy world. A missing file is created (empty world,
    // current schema, atomically through a temporary file and a rename) when createIfMissing, otherwise
    // it is an error.
    static std::unique_ptr<WorldStore> open(const std::filesystem::path& file, bool createIfMissing);
    // The same validation and loading for a world held in memory (the bytes of a world file), named `name` in
    // messages: no file is read or written, and save() is not available (it throws). For tests and fuzzers,
    // which run thousands of worlds a second this way.
    static std::unique_ptr<WorldStore> openImage(std::span<const unsigned char> bytes, const std::string& name);
    // The bytes of a world file holding `snapshot`, made as save() makes a file (including its read-back
    // check); openImage() or a file with these bytes loads it.
    static std::vector<unsigned char> toImage(const Snapshot& snapshot);

    bool isNew() const { return m_isNew; } // no world saved in the file yet: nothing to load
    // The world as validated by open(). Throws WorldFileError when there is nothing to load (isNew()).
    Snapshot load();
    // Recovery notes and skipped records ("FILE: table T, row R: skipped: why").
    const std::vector<std::string>& warnings() const { return m_warnings; }
    // One transaction (migrating an older schema in the same transaction). Throws WorldFileError on
    // failure (disk full, file deleted or made read-only, replaced by another file...); the file then
    // still holds the previous save.
    void save(const Snapshot& snapshot);
    const std::filesystem::path& path() const { return m_path; }

private:
    explicit WorldStore(std::filesystem::path file) : m_path(std::move(file)) {}
    void readValidated(sqlite3* db); // version, quick_check, then every record (throws WorldFileError)
    std::filesystem::path m_path;
    bool m_isNew = false;
    bool m_inMemory = false; // openImage(): no file behind it
    std::optional<Snapshot> m_loaded;
    std::vector<std::string> m_warnings;
    std::mutex m_saveMutex; // one save at a time
};

} // namespace save
