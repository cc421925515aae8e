// What the world store's units share, and nothing else includes (the public interface is save/world_store.h):
// error helpers, small RAII wrappers around SQLite's C API, the column lists, and the reader that both loading
// and saving use. The units: world_schema.cpp (the tables, creating a file, migrations, the column lists),
// record_checks.cpp (what refuses or repairs a record), world_load.cpp (open(): a file into a Snapshot) and
// world_save.cpp (save(): a Snapshot into a file); world_store.cpp holds the hair blob, takeSnapshot, restore
// and removeWorldFiles.
#pragma once
#include <sqlite3.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "save/world_store.h"
#include "world/collision.h"
#include "world/world.h"

namespace save {

// ---- errors ------------------------------------------------------------------------------------------

inline std::string fileName(const std::filesystem::path& p) { return p.string(); }

[[noreturn]] inline void fail(const std::filesystem::path& file, const std::string& what) {
    throw WorldFileError(fileName(file) + ": " + what);
}

// A value in one record that cannot be trusted; caught per record (skip) or per file (throw).
struct BadValue : std::runtime_error {
    using runtime_error::runtime_error;
};

// A record that refuses the whole load rather than being skipped (a hair ball's solver this build lacks).
struct RefusedRecord : WorldFileError {
    using WorldFileError::WorldFileError;
};

// ---- SQLite --------------------------------------------------------------------------------------------

struct Db {
    sqlite3* h = nullptr;
    Db() = default;
    Db(const Db&) = delete;
    Db& operator=(const Db&) = delete;
    ~Db() {
        if (h) sqlite3_close_v2(h);
    }
};

class Stmt {
public:
    Stmt(sqlite3* db, const std::filesystem::path& file, const char* sql) : m_db(db), m_file(file) {
        if (sqlite3_prepare_v2(db, sql, -1, &m_st, nullptr) != SQLITE_OK) {
            fail(file, std::string("damaged or not a Minecrappy world: ") + sqlite3_errmsg(db));
        }
    }
    Stmt(const Stmt&) = delete;
    Stmt& operator=(const Stmt&) = delete;
    ~Stmt() { sqlite3_finalize(m_st); }
    sqlite3_stmt* get() const { return m_st; }
    // True while there is a row; throws on an error.
    bool step() {
        const int rc = sqlite3_step(m_st);
        if (rc == SQLITE_ROW) return true;
        if (rc == SQLITE_DONE) return false;
        if ((rc & 0xff) == SQLITE_CORRUPT || (rc & 0xff) == SQLITE_NOTADB) {
            fail(m_file, std::string("is damaged: ") + sqlite3_errmsg(m_db));
        }
        fail(m_file, std::string("cannot read or write: ") + sqlite3_errmsg(m_db));
    }
    void run() {
        while (step()) {}
        sqlite3_reset(m_st);
        sqlite3_clear_bindings(m_st);
    }
    void bind(int i, double v) { sqlite3_bind_double(m_st, i, v); }
    void bind(int i, std::int64_t v) { sqlite3_bind_int64(m_st, i, v); }
    void bind(int i, int v) { sqlite3_bind_int64(m_st, i, v); }
    void bind(int i, bool v) { sqlite3_bind_int64(m_st, i, v ? 1 : 0); }
    void bind(int i, const std::string& v) {
        sqlite3_bind_text(m_st, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    }
    void bindBlob(int i, const std::vector<unsigned char>& v) {
        sqlite3_bind_blob(m_st, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    }

    // Typed, validated column reads (throw BadValue naming the column).
    double real(int c, const char* name) const {
        const int t = sqlite3_column_type(m_st, c);
        if (t != SQLITE_FLOAT && t != SQLITE_INTEGER) throw BadValue(std::string(name) + " is not a number");
        const double v = sqlite3_column_double(m_st, c);
        if (!std::isfinite(v)) throw BadValue(std::string(name) + " is not finite");
        return v;
    }
    float real32(int c, const char* name) const {
        const float v = static_cast<float>(real(c, name));
        if (!std::isfinite(v)) throw BadValue(std::string(name) + " is out of range for a float");
        return v;
    }
    std::int64_t integer(int c, const char* name) const {
        if (sqlite3_column_type(m_st, c) != SQLITE_INTEGER) throw BadValue(std::string(name) + " is not an integer");
        return sqlite3_column_int64(m_st, c);
    }
    int intIn(int c, const char* name, std::int64_t lo, std::int64_t hi) const {
        const std::int64_t v = integer(c, name);
        if (v < lo || v > hi) {
            throw BadValue(std::string(name) + " = " + std::to_string(v) + " is outside " + std::to_string(lo) + ".." +
                           std::to_string(hi));
        }
        return static_cast<int>(v);
    }
    bool flag(int c, const char* name) const { return intIn(c, name, 0, 1) != 0; }
    std::string text(int c, const char* name) const {
        if (sqlite3_column_type(m_st, c) != SQLITE_TEXT) throw BadValue(std::string(name) + " is not text");
        const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(m_st, c));
        return std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(m_st, c)));
    }

private:
    sqlite3* m_db;
    const std::filesystem::path& m_file;
    sqlite3_stmt* m_st = nullptr;
};

inline void exec(sqlite3* db, const std::filesystem::path& file, const char* sql) {
    char* err = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
        const std::string msg = err ? err : sqlite3_errmsg(db);
        sqlite3_free(err);
        fail(file, "cannot write: " + msg);
    }
}

inline std::int64_t pragmaInt(sqlite3* db, const std::filesystem::path& file, const char* pragma) {
    Stmt s(db, file, pragma);
    if (!s.step()) fail(file, std::string("damaged: ") + pragma + " returned nothing");
    return sqlite3_column_int64(s.get(), 0);
}

// Write pragmas and the writable-file test (world_save.cpp); createWorld and open() use them too.
void setWritePragmas(sqlite3* db, const std::filesystem::path& file);
bool readOnlyFile(const std::filesystem::path& file);

// ---- the schema (world_schema.cpp) -----------------------------------------------------------------------

std::string currentSchemaSql(); // the tables of a new world: v1's and every migration's
// Runs the migrations from schema `version` up to kSchemaVersion and sets user_version, inside the caller's
// transaction.
void migrateToCurrent(sqlite3* db, const std::filesystem::path& file, std::int64_t version);
// A new, empty world at `file` with the current schema (never replacing a file that is there).
void createWorld(const std::filesystem::path& file);

// Each table's listed columns (game/state_fields.h's lists), in the list's order; meta's are its keys.
std::vector<std::string> metaKeys();
std::vector<std::string> playerColumns();
std::vector<std::string> setColumns();
std::vector<std::string> slotColumns();
std::vector<std::string> ballColumns();

// ---- edits: one blob per chunk, 3 bytes per edit: local index (x + 32 (z + 32 y)) as u16 LE, block id --

inline constexpr std::size_t kEditBytes = 3;

// ---- reading: world_load.cpp, with the checks of record_checks.cpp ---------------------------------------

// Reads every table into a Snapshot: a record that cannot be trusted is skipped (the player: reset) with a
// warning naming the file, table and row. open() reads a file with it, and save() its own transaction.
class RecordReader {
public:
    RecordReader(sqlite3* db, const std::filesystem::path& file, std::vector<std::string>& warnings)
        : m_db(db), m_file(file), m_warnings(warnings) {}

    // nullopt: the file holds no world yet (created, never saved).
    std::optional<Snapshot> read(int version);

private:
    void warn(const char* table, const std::string& row, const std::string& why);

    // A query of a table's keys, then the listed columns this file has, indexed by name for ColumnReader. A
    // listed column missing from a file of the current schema is damage; in an older file it is one a later
    // schema added, and its field keeps the default.
    struct Selection {
        std::string sql;
        std::map<std::string, int> index;
    };
    Selection select(const char* table, std::initializer_list<const char*> keys, const std::vector<std::string>& listed,
                     const char* orderBy);

    bool readMeta(Snapshot& s);
    void readPlayer(Snapshot& s);
    void readEdits(Snapshot& s);
    void readPendulums(Snapshot& s);
    void readHairBalls(Snapshot& s);

    // The checks (record_checks.cpp): each throws BadValue saying why the record cannot be trusted, or repairs
    // it and warns.
    static void checkMeta(const game::StateMeta& meta);
    static void checkPlayer(const game::Player& p);
    void placePlayer(game::Player& p);
    std::string editProblem(unsigned index, unsigned block, std::set<unsigned>& seen) const;
    void checkPendulumSet(PendulumSetRecord& rec, const std::string& row);
    void checkSolver(const std::string& name, const std::string& row) const;
    static void checkHairBall(const HairBallRecord& rec);
    void checkHairBallPlace(const HairBallRecord& rec, const Snapshot& s) const;

    int m_version = kSchemaVersion;
    std::optional<world::World> m_world; // the terrain and the edits, from readEdits on
    std::vector<std::string> m_ballRows; // the row of each ball kept so far
    std::vector<std::string> m_setRows;  // and of each set, with its boxes (game::pendulumSetBoxes)
    std::vector<std::array<world::Aabb, 5>> m_setBoxes;
    sqlite3* m_db;
    const std::filesystem::path& m_file;
    std::vector<std::string>& m_warnings;
};

} // namespace save
