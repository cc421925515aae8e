// The world file's schema: the tables each version created (kSchemaV1Sql and what each later version adds),
// the migrations that bring an older file up to date, the making of a new file, and the columns each table
// holds for its field list (game/state_fields.h). A new field is a column here (a new schema version and its
// migration); its check is in record_checks.cpp, its reading in world_load.cpp, its writing in world_save.cpp.
#include "save/store_internal.h"

#include <fcntl.h>
#include <unistd.h>

namespace save {

const char* const kSchemaV1Sql = R"sql(
CREATE TABLE meta (key TEXT PRIMARY KEY NOT NULL, value NOT NULL);
CREATE TABLE player (
  id INTEGER PRIMARY KEY CHECK (id = 0),
  px REAL, py REAL, pz REAL, vx REAL, vy REAL, vz REAL, yaw REAL, pitch REAL,
  on_ground INTEGER, flying INTEGER, selected_slot INTEGER, hotbar TEXT);
CREATE TABLE chunk_edits (
  cx INTEGER NOT NULL, cy INTEGER NOT NULL, cz INTEGER NOT NULL, edits BLOB NOT NULL,
  PRIMARY KEY (cx, cy, cz));
CREATE TABLE pendulum_sets (
  id INTEGER PRIMARY KEY, x INTEGER, y INTEGER, z INTEGER,
  release_degrees REAL, length REAL, gravity REAL, step_multiplier REAL,
  released INTEGER, previous_time REAL);
CREATE TABLE pendulum_slots (
  set_id INTEGER NOT NULL, slot INTEGER NOT NULL, method TEXT, diverged INTEGER,
  drawn_theta REAL, drawn_omega REAL, theta REAL, omega REAL, time REAL, time_carry REAL,
  previous_theta REAL, previous_omega REAL, last_step REAL, cart_x REAL, cart_y REAL, sin_theta REAL,
  exact_theta0 REAL, exact_omega0 REAL,
  PRIMARY KEY (set_id, slot));
)sql";

// What v2 adds to v1 (also the v1 -> v2 migration).
const char* const kSchemaV2Sql = R"sql(
CREATE TABLE hair_balls (
  id INTEGER PRIMARY KEY, cx REAL, cy REAL, cz REAL, spin REAL, radius REAL, red REAL, green REAL, blue REAL,
  spin_rate REAL, strands INTEGER, nodes_per_strand INTEGER, strand_length REAL, damping REAL, gravity REAL,
  iterations INTEGER, substeps INTEGER, patch_half_angle REAL, seed INTEGER, max_substep_seconds REAL,
  sleep_speed REAL, sleep_delay REAL, velocity_correction REAL);
)sql";

// What v3 adds to v2 (also the v2 -> v3 migration): each hair ball's solver, by name (physics::hairMethodName).
// A v2 file's balls were all stepped by dftl; the loader gives them that.
const char* const kSchemaV3Sql = R"sql(
ALTER TABLE hair_balls ADD COLUMN solver TEXT;
)sql";

// What v4 adds to v3 (also the v3 -> v4 migration): each hair ball's hair as it was (encodeHairState). A v3
// file's balls have none: their hair starts anew from the spawn pose, and the load says so.
const char* const kSchemaV4Sql = R"sql(
ALTER TABLE hair_balls ADD COLUMN hair_state BLOB;
)sql";

// What v5 adds to v4: no table. The meta table gains the day clock's keys (time_of_day, day_length,
// day_stopped; a v4 file has none and opens at game::kDefaultHours), and the chunk_edits blobs may hold the lamp
// (world::BlockType::Lamp). A build that reads up to v4 refuses a v5 file whole ("this build reads up to 4"),
// rather than misreading a lamp or dropping the time.
const char* const kSchemaV5Sql = "";

// What v6 adds to v5 (also the v5 -> v6 migration): whether each hair ball's own sphere is a collider for its
// hair (`hair N host_collision=false`), which an older file's balls all were.
const char* const kSchemaV6Sql = R"sql(
ALTER TABLE hair_balls ADD COLUMN host_collision INTEGER DEFAULT 1;
)sql";

// What v7 adds to v6: no table. The chunk_edits blobs may hold the coloured lamps (world::BlockType::RedLamp to
// OrangeLamp); the white lamp keeps its id, so an older world's lamps stay white.
const char* const kSchemaV7Sql = "";

int blockIdsOfSchema(int version) {
    if (version >= 7) return world::kBlockTypeCount;
    return static_cast<int>(version >= 5 ? world::BlockType::Lamp : world::BlockType::Gravel) + 1;
}
static_assert(static_cast<int>(world::BlockType::OrangeLamp) + 1 == world::kBlockTypeCount,
              "a new block is a schema step: give it a version in blockIdsOfSchema");

namespace {

// Migrations[v] takes a file from schema v to v + 1.
const std::map<int, const char*> kMigrations = {{1, kSchemaV2Sql}, {2, kSchemaV3Sql}, {3, kSchemaV4Sql},
                                                {4, kSchemaV5Sql}, {5, kSchemaV6Sql}, {6, kSchemaV7Sql}};

void syncDirectory(const std::filesystem::path& dir) {
    const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd >= 0) {
        (void)::fsync(fd);
        ::close(fd);
    }
}

// A record's columns in the order its field list visits them.
struct ColumnNames {
    std::vector<std::string> names;
    template <class T>
    void value(const char* name, const T& /*x*/) {
        names.emplace_back(name);
    }
    template <class T>
    void vec(const char* /*name*/, const T& /*x*/, game::Columns columns) {
        for (const char* c : columns) names.emplace_back(c);
    }
    template <class T>
    void hotbar(const char* name, const T& /*items*/) {
        names.emplace_back(name);
    }
    template <class H>
    void hair(const char* name, const H& /*hair*/, int /*strands*/, int /*nodes*/) {
        names.emplace_back(name);
    }
};

template <class Visit>
std::vector<std::string> namesOf(Visit visit) {
    ColumnNames n;
    visit(n);
    return n.names;
}

} // namespace

// The tables of a new world, file or image: v1's and every migration's.
std::string currentSchemaSql() {
    std::string sql = kSchemaV1Sql;
    for (const auto& [version, migration] : kMigrations) sql += migration;
    return sql;
}

void migrateToCurrent(sqlite3* db, const std::filesystem::path& file, std::int64_t version) {
    for (; version < kSchemaVersion; ++version) exec(db, file, kMigrations.at(static_cast<int>(version)));
    exec(db, file, ("PRAGMA user_version=" + std::to_string(kSchemaVersion)).c_str());
}

void createWorld(const std::filesystem::path& file) {
    // Built beside the target and renamed into place, so a crash never leaves a half-made world behind.
    std::filesystem::path tmp = file;
    tmp += ".creating";
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    {
        Db db;
        if (sqlite3_open_v2(tmp.c_str(), &db.h, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
            fail(file, std::string("cannot create: ") + (db.h ? sqlite3_errmsg(db.h) : "out of memory"));
        }
        setWritePragmas(db.h, file);
        std::string sql = "BEGIN IMMEDIATE; PRAGMA application_id=" + std::to_string(kApplicationId) + "; ";
        sql += currentSchemaSql();
        sql += "PRAGMA user_version=" + std::to_string(kSchemaVersion) + "; COMMIT;";
        try {
            exec(db.h, file, sql.c_str());
        } catch (...) {
            std::filesystem::remove(tmp, ec);
            throw;
        }
    }
    if (std::filesystem::exists(file, ec)) { // created by someone else meanwhile: never replace it
        std::filesystem::remove(tmp, ec);
        fail(file, "appeared while a new world was being created; not replaced");
    }
    std::filesystem::rename(tmp, file, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        fail(file, "cannot create: " + ec.message());
    }
    syncDirectory(file.parent_path());
}

// ---- the field lists as columns (game/state_fields.h) ----------------------------------------------

std::vector<std::string> metaKeys() {
    return namesOf([](ColumnNames& n) {
        game::StateMeta m;
        game::visitMeta(n, m);
    });
}
std::vector<std::string> playerColumns() {
    return namesOf([](ColumnNames& n) {
        game::Player p;
        game::visitPlayer(n, p);
    });
}
std::vector<std::string> setColumns() {
    return namesOf([](ColumnNames& n) {
        PendulumSetRecord r;
        game::visitPendulumSet(n, r);
    });
}
std::vector<std::string> slotColumns() {
    return namesOf([](ColumnNames& n) {
        PendulumSetRecord r;
        game::visitPendulumSlot(n, r, 0);
    });
}
std::vector<std::string> ballColumns() {
    return namesOf([](ColumnNames& n) {
        HairBallRecord r;
        game::visitHairBall(n, r, r.hair);
    });
}

std::vector<std::string> listedColumns(const std::string& table) {
    if (table == "meta") return metaKeys();
    if (table == "player") return playerColumns();
    if (table == "pendulum_sets") return setColumns();
    if (table == "pendulum_slots") return slotColumns();
    if (table == "hair_balls") return ballColumns();
    throw std::invalid_argument("no field list for table " + table);
}

std::vector<std::string> keyColumns(const std::string& table) {
    if (table == "meta") return {"key", "value"};
    if (table == "pendulum_slots") return {"set_id", "slot"};
    if (table == "player" || table == "pendulum_sets" || table == "hair_balls") return {"id"};
    throw std::invalid_argument("no field list for table " + table);
}

} // namespace save
