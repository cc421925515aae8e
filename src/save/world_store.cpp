// World files through SQLite's C API. Layout of the code: small RAII wrappers and error helpers; the schema;
// reading with validation (read-only connection); writing (one transaction per save); open().
#include "save/world_store.h"

#include <sqlite3.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <glm/geometric.hpp>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <string_view>
#include <type_traits>

#include <fcntl.h>
#include <unistd.h>

#include "core/quote.h"
#include "game/hair_ball.h"
#include "game/player.h"
#include "game/space.h"
#include "game/state_io.h"
#include "world/chunk.h"

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

namespace {

// Migrations[v] takes a file from schema v to v + 1.
const std::map<int, const char*> kMigrations = {{1, kSchemaV2Sql}, {2, kSchemaV3Sql}, {3, kSchemaV4Sql}};

// The tables of a new world, file or image: v1's and every migration's.
std::string currentSchemaSql() {
    std::string sql = kSchemaV1Sql;
    for (const auto& [version, migration] : kMigrations) sql += migration;
    return sql;
}

// The hair blob: "MCH2", little-endian u32 strands and u32 nodes per strand, then physics::visitHairState's
// fields in its order: an int as i32, a float as f32, a bool as one byte 0 or 1, a u64, a vector or quaternion
// as its f32 components in glm's order, a node array as strands x nodes f32 (node-major). ("MCH1", the layout of
// the first schema 4 builds, had a pad byte after the flags; its hair starts anew.)
constexpr unsigned char kHairMagic[4] = {'M', 'C', 'H', '2'};
static_assert(std::endian::native == std::endian::little, "the hair blob is written in the machine's byte order");

template <typename T>
void put(std::vector<unsigned char>& out, T v) {
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    out.insert(out.end(), p, p + sizeof v);
}

// Reads fixed-size values off the front of a blob; throws std::invalid_argument when it runs out.
struct BlobReader {
    const unsigned char* p;
    std::size_t left;
    template <typename T>
    T get(const char* what) {
        if (left < sizeof(T)) throw std::invalid_argument(std::string("hair_state is cut short at ") + what);
        T v;
        std::memcpy(&v, p, sizeof v);
        p += sizeof v;
        left -= sizeof v;
        return v;
    }
};

struct HairBlobWriter {
    std::vector<unsigned char>& out;
    template <typename T>
    void value(const char* /*name*/, const T& x) {
        if constexpr (std::is_same_v<T, bool>) {
            put(out, static_cast<std::uint8_t>(x ? 1 : 0));
        } else if constexpr (std::is_arithmetic_v<T>) {
            put(out, x);
        } else {
            for (decltype(T::length()) i = 0; i < T::length(); ++i) put(out, x[i]);
        }
    }
    void nodes(const char* /*name*/, const std::vector<float>& a) {
        const auto* p = reinterpret_cast<const unsigned char*>(a.data());
        out.insert(out.end(), p, p + a.size() * sizeof(float));
    }
};

struct HairBlobReader {
    BlobReader& r;
    std::size_t count; // nodes of the ball
    template <typename T>
    void value(const char* name, T& x) {
        if constexpr (std::is_same_v<T, bool>) {
            const auto b = r.get<std::uint8_t>(name);
            if (b > 1) throw std::invalid_argument(std::string("hair_state's ") + name + " is neither 0 nor 1");
            x = b != 0;
        } else if constexpr (std::is_arithmetic_v<T>) {
            x = r.get<T>(name);
        } else {
            for (decltype(T::length()) i = 0; i < T::length(); ++i) x[i] = r.get<float>(name);
        }
    }
    void nodes(const char* name, std::vector<float>& a) {
        if (r.left < count * sizeof(float))
            throw std::invalid_argument(std::string("hair_state is cut short in node array ") + name + " (" +
                                        std::to_string(r.left) + " bytes left of " +
                                        std::to_string(count * sizeof(float)) + ")");
        a.resize(count);
        std::memcpy(a.data(), r.p, count * sizeof(float));
        r.p += count * sizeof(float);
        r.left -= count * sizeof(float);
    }
};

} // namespace

std::vector<unsigned char> encodeHairState(const physics::HairSolverState& s, int strands, int nodesPerStrand) {
    std::vector<unsigned char> out(kHairMagic, kHairMagic + 4);
    put(out, static_cast<std::uint32_t>(strands));
    put(out, static_cast<std::uint32_t>(nodesPerStrand));
    HairBlobWriter w{out};
    physics::visitHairState(s, w);
    return out;
}

physics::HairSolverState decodeHairState(std::span<const unsigned char> blob, int strands, int nodesPerStrand) {
    BlobReader r{blob.data(), blob.size()};
    unsigned char magic[4];
    for (unsigned char& m : magic) m = r.get<unsigned char>("its tag");
    if (std::memcmp(magic, "MCH1", 4) == 0)
        throw std::invalid_argument("hair_state is of the first schema 4 builds' layout (MCH1)");
    if (std::memcmp(magic, kHairMagic, 4) != 0)
        throw std::invalid_argument("hair_state is not a hair blob (no MCH2 tag)");
    const auto savedStrands = r.get<std::uint32_t>("strands"), savedNodes = r.get<std::uint32_t>("nodes");
    if (savedStrands != static_cast<std::uint32_t>(strands) || savedNodes != static_cast<std::uint32_t>(nodesPerStrand))
        throw std::invalid_argument("hair_state is of " + std::to_string(savedStrands) + " x " +
                                    std::to_string(savedNodes) + " nodes, the ball has " + std::to_string(strands) +
                                    " x " + std::to_string(nodesPerStrand));
    physics::HairSolverState s;
    HairBlobReader fields{r, static_cast<std::size_t>(strands) * static_cast<std::size_t>(nodesPerStrand)};
    physics::visitHairState(s, fields);
    if (r.left != 0) throw std::invalid_argument("hair_state has " + std::to_string(r.left) + " bytes past its nodes");
    return s;
}

namespace {

std::string fileName(const std::filesystem::path& p) { return p.string(); }

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
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

void exec(sqlite3* db, const std::filesystem::path& file, const char* sql) {
    char* err = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
        const std::string msg = err ? err : sqlite3_errmsg(db);
        sqlite3_free(err);
        fail(file, "cannot write: " + msg);
    }
}

std::int64_t pragmaInt(sqlite3* db, const std::filesystem::path& file, const char* pragma) {
    Stmt s(db, file, pragma);
    if (!s.step()) fail(file, std::string("damaged: ") + pragma + " returned nothing");
    return sqlite3_column_int64(s.get(), 0);
}

// ---- items -------------------------------------------------------------------------------------------

std::optional<game::Item> itemFromName(std::string_view name) {
    if (name == "pendulum_set") return game::Item::pendulumSet();
    if (name == "hair_ball") return game::Item::hairBall();
    const auto b = world::blockFromName(name);
    if (!b || *b == world::BlockType::Air) return std::nullopt;
    return game::Item::ofBlock(*b);
}

// ---- edits: one blob per chunk, 3 bytes per edit: local index (x + 32 (z + 32 y)) as u16 LE, block id --

constexpr std::size_t kEditBytes = 3;

std::uint16_t localIndex(glm::ivec3 local) {
    return static_cast<std::uint16_t>(local.x + world::kChunkSize * (local.z + world::kChunkSize * local.y));
}

// A coordinate or state value for a message: %g, so 1e300 reads as 1e+300.
std::string formatCoordinate(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// ---- the field lists as columns (game/state_fields.h) ----------------------------------------------

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

// "INSERT INTO table (keys..., columns...) VALUES (?1, ...)"
std::string insertSql(const char* table, std::initializer_list<const char*> keys,
                      const std::vector<std::string>& columns) {
    std::string names, values;
    int n = 0;
    const auto add = [&](const std::string& name) {
        names += (n ? ", " : "") + name;
        values += (n ? ", ?" : "?") + std::to_string(n + 1);
        ++n;
    };
    for (const char* k : keys) add(k);
    for (const auto& c : columns) add(c);
    return std::string("INSERT INTO ") + table + " (" + names + ") VALUES (" + values + ")";
}

// Binds a record's fields to an INSERT's parameters from `next` on, in the list's order.
struct Binder {
    Stmt& st;
    int next;
    template <class T>
    void value(const char* /*name*/, const T& x) {
        if constexpr (std::is_enum_v<T>) {
            st.bind(next++, std::string(game::enumName(x)));
        } else if constexpr (std::is_same_v<T, bool>) {
            st.bind(next++, x);
        } else if constexpr (std::is_floating_point_v<T>) {
            st.bind(next++, static_cast<double>(x));
        } else if constexpr (std::is_same_v<T, std::uint64_t>) {
            st.bind(next++, static_cast<std::int64_t>(x)); // SQLite's integers are signed; read back as cast
        } else {
            static_assert(std::is_same_v<T, int>);
            st.bind(next++, x);
        }
    }
    template <class T>
    void vec(const char* name, const T& x, game::Columns /*columns*/) {
        for (int i = 0; i < 3; ++i) value(name, x[i]);
    }
    void hotbar(const char* /*name*/, const std::array<game::Item, game::kHotbarSize>& items) {
        std::string s;
        for (const auto& item : items) {
            if (!s.empty()) s += ',';
            s += game::itemName(item);
        }
        st.bind(next++, s);
    }
    void hair(const char* /*name*/, const std::optional<physics::HairSolverState>& hair, int strands, int nodes) {
        if (hair) st.bindBlob(next, encodeHairState(*hair, strands, nodes));
        ++next; // none: NULL
    }
};

// The meta table's rows: a key and its value for each field of game::visitMeta.
struct MetaRowWriter {
    Stmt& st;
    template <class T>
    void value(const char* name, const T& x) {
        st.bind(1, std::string(name));
        Binder{st, 2}.value(name, x);
        st.run();
    }
};

// Reads a record's fields from a row by column name, each checked for its type (BadValue naming the column).
// A listed column the query lacks (a later schema added it; see RecordReader::select) leaves the field's default.
struct ColumnReader {
    const Stmt& st;
    const std::map<std::string, int>& index;
    // The hair blob: no column (an older schema), NULL, or its bytes.
    enum class Hair { Absent, Missing, Present } hairRead = Hair::Absent;
    std::vector<unsigned char> hairBlob{};

    std::optional<int> column(const char* name) const {
        const auto it = index.find(name);
        return it == index.end() ? std::nullopt : std::optional<int>(it->second);
    }
    template <class T>
    void value(const char* name, T& x) {
        const auto c = column(name);
        if (!c) return;
        if constexpr (std::is_enum_v<T>) {
            const std::string text = st.text(*c, name);
            const auto v = game::enumFromName(text, x);
            if (!v) throw BadValue(std::string(name) + " '" + text + "' is unknown");
            x = *v;
        } else if constexpr (std::is_same_v<T, bool>) {
            x = st.flag(*c, name);
        } else if constexpr (std::is_same_v<T, float>) {
            x = st.real32(*c, name);
        } else if constexpr (std::is_same_v<T, double>) {
            x = st.real(*c, name);
        } else if constexpr (std::is_same_v<T, std::uint64_t>) {
            x = static_cast<std::uint64_t>(st.integer(*c, name));
        } else {
            static_assert(std::is_same_v<T, int>);
            x = st.intIn(*c, name, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
        }
    }
    template <class T>
    void vec(const char* /*name*/, T& x, game::Columns columns) {
        for (int i = 0; i < 3; ++i) value(columns[static_cast<std::size_t>(i)], x[i]);
    }
    void hotbar(const char* name, std::array<game::Item, game::kHotbarSize>& items) {
        const auto c = column(name);
        if (!c) return;
        const std::string text = st.text(*c, name);
        std::size_t start = 0;
        for (auto& item : items) {
            if (start > text.size())
                throw BadValue("hotbar has fewer than " + std::to_string(game::kHotbarSize) + " items");
            const std::size_t end = std::min(text.find(',', start), text.size());
            const std::string itemText = text.substr(start, end - start);
            const auto parsed = itemFromName(itemText);
            if (!parsed) throw BadValue("hotbar item '" + itemText + "' is unknown");
            item = *parsed;
            start = end + 1;
        }
        if (start <= text.size())
            throw BadValue("hotbar has more than " + std::to_string(game::kHotbarSize) + " items");
    }
    // Only taken here: the caller decodes it once the ball's size is known to be sane.
    void hair(const char* name, std::optional<physics::HairSolverState>& /*hair*/, int /*strands*/, int /*nodes*/) {
        const auto c = column(name);
        if (!c) return;
        if (sqlite3_column_type(st.get(), *c) != SQLITE_BLOB) {
            hairRead = Hair::Missing;
            return;
        }
        const auto* data = static_cast<const unsigned char*>(sqlite3_column_blob(st.get(), *c));
        hairBlob.assign(data, data + sqlite3_column_bytes(st.get(), *c));
        hairRead = Hair::Present;
    }
};

// ---- reading -----------------------------------------------------------------------------------------

class RecordReader {
public:
    RecordReader(sqlite3* db, const std::filesystem::path& file, std::vector<std::string>& warnings)
        : m_db(db), m_file(file), m_warnings(warnings) {}

    // nullopt: the file holds no world yet (created, never saved).
    std::optional<Snapshot> read(int version) {
        m_version = version;
        Snapshot s;
        if (!readMeta(s)) return std::nullopt;
        readEdits(s);
        // The blocks as the game will see them, for the checks a placement would meet.
        m_world.emplace(s.terrain);
        for (const auto& e : s.edits) m_world->set(e.pos, e.block);
        readPlayer(s);
        readPendulums(s);
        if (version >= 2) readHairBalls(s);
        return s;
    }

private:
    void warn(const char* table, const std::string& row, const std::string& why) {
        m_warnings.push_back(fileName(m_file) + ": table " + table + ", row " + row + ": skipped: " + why);
    }

    // A query of a table's keys, then the listed columns this file has, indexed by name for ColumnReader. A
    // listed column missing from a file of the current schema is damage; in an older file it is one a later
    // schema added, and its field keeps the default.
    struct Selection {
        std::string sql;
        std::map<std::string, int> index;
    };
    Selection select(const char* table, std::initializer_list<const char*> keys, const std::vector<std::string>& listed,
                     const char* orderBy) {
        std::set<std::string> has;
        {
            Stmt info(m_db, m_file, (std::string("PRAGMA table_info(") + table + ")").c_str());
            while (info.step()) has.insert(info.text(1, "column name"));
        }
        Selection s;
        std::string names;
        const auto add = [&](const std::string& name) {
            s.index.emplace(name, static_cast<int>(s.index.size()));
            names += (names.empty() ? "" : ", ") + name;
        };
        for (const char* k : keys) add(k);
        for (const auto& c : listed) {
            if (has.count(c)) {
                add(c);
            } else if (m_version >= kSchemaVersion) {
                fail(m_file, std::string("is damaged: table ") + table + " has no column " + c);
            }
        }
        s.sql = "SELECT " + names + " FROM " + table + (orderBy ? std::string(" ORDER BY ") + orderBy : "");
        return s;
    }

    bool readMeta(Snapshot& s) {
        {
            Stmt any(m_db, m_file, "SELECT count(*) FROM meta");
            if (!any.step() || sqlite3_column_int64(any.get(), 0) == 0) return false;
        }
        try {
            // The state's own values (game::visitMeta): a key/value row each, all required.
            game::StateMeta meta;
            for (const std::string& key : metaKeys()) {
                Stmt st(m_db, m_file, "SELECT value FROM meta WHERE key = ?1");
                st.bind(1, key);
                if (!st.step()) fail(m_file, "bad world settings (table meta): no '" + key + "'");
                const std::map<std::string, int> index{{key, 0}}; // this key's value; the others' are absent
                ColumnReader r{st, index};
                game::visitMeta(r, meta);
            }
            if (static_cast<std::int64_t>(meta.tick) < 0) throw BadValue("meta tick is negative");
            s.tick = meta.tick;
            s.terrain.seed = meta.seed;
            s.terrain.kind = meta.terrain;
            s.paused = meta.paused;
            // Beside the state: the hash and the count of the saves, each optional.
            Stmt st(m_db, m_file, "SELECT key, value FROM meta WHERE key IN ('state_hash', 'save_count')");
            while (st.step()) {
                if (st.text(0, "meta key") == "state_hash") {
                    const std::string hex = st.text(1, "meta state_hash");
                    char* end = nullptr;
                    s.stateHash = std::strtoull(hex.c_str(), &end, 16);
                    if (hex.size() != 16 || *end != '\0') throw BadValue("meta state_hash is not 16 hex digits");
                } else {
                    const std::int64_t n = st.integer(1, "meta save_count");
                    if (n < 0) throw BadValue("meta save_count is negative");
                    s.saveCount = static_cast<std::uint64_t>(n);
                }
            }
        } catch (const BadValue& e) {
            fail(m_file, std::string("bad world settings (table meta): ") + e.what());
        }
        return true;
    }

    // A bad player record costs the player's place, never the world: the player is reset to the spawn point
    // (restore() does it) with a warning naming the file, table and row.
    void readPlayer(Snapshot& s) {
        const Selection q = select("player", {}, playerColumns(), nullptr);
        Stmt st(m_db, m_file, q.sql.c_str());
        if (!st.step()) {
            m_warnings.push_back(fileName(m_file) + ": table player: no row; the player starts at the spawn point");
            s.resetPlayer = true;
            return;
        }
        game::Player p;
        try {
            ColumnReader r{st, q.index};
            game::visitPlayer(r, p);
            if (!game::insideBorder(p.position)) throw BadValue("position is outside the world border");
            // The game's fastest motion is a 60 m/s fall; a saved velocity far beyond it is not the game's.
            constexpr float kFastest = 1000.0f;
            if (!(glm::length(p.velocity) <= kFastest)) throw BadValue("velocity is above 1000 m/s");
            if (!(p.yaw >= 0.0f && p.yaw < 360.0f)) throw BadValue("yaw is outside [0, 360)");
            if (std::abs(p.pitch) > 89.0f) throw BadValue("pitch is outside -89..89");
            if (p.selectedSlot < 0 || p.selectedSlot >= game::kHotbarSize)
                throw BadValue("selected_slot = " + std::to_string(p.selectedSlot) + " is outside 0.." +
                               std::to_string(game::kHotbarSize - 1));
            if (st.step()) throw BadValue("there is more than one row");
        } catch (const BadValue& e) {
            m_warnings.push_back(fileName(m_file) + ": table player, row 0: reset to the spawn point: " + e.what());
            s.resetPlayer = true;
            return;
        }
        // Inside blocks (a world edited by hand): lifted out as after a teleport, and said.
        const float savedY = p.position.y;
        if (game::liftOutOfBlocks(p, *m_world)) {
            m_warnings.push_back(fileName(m_file) + ": table player, row 0: inside blocks at y = " +
                                 formatCoordinate(savedY) + ": lifted to y = " + formatCoordinate(p.position.y));
        }
        s.player = p;
    }

    void readEdits(Snapshot& s) {
        Stmt st(m_db, m_file, "SELECT cx, cy, cz, edits FROM chunk_edits ORDER BY cx, cy, cz");
        while (st.step()) {
            std::string row = "?";
            try {
                // Chunks past the world border (game/space.h) hold nothing a player can reach.
                constexpr std::int64_t kFarChunk =
                    static_cast<std::int64_t>(game::kWorldBorder) / world::kChunkSize + 1;
                const int cx = st.intIn(0, "cx", -kFarChunk, kFarChunk);
                const int cz = st.intIn(2, "cz", -kFarChunk, kFarChunk);
                const int cy = st.intIn(1, "cy", 0, world::kWorldHeightChunks - 1);
                // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
                row = "(";
                row += std::to_string(cx);
                row += ", ";
                row += std::to_string(cy);
                row += ", ";
                row += std::to_string(cz);
                row += ")";
                if (sqlite3_column_type(st.get(), 3) != SQLITE_BLOB) throw BadValue("edits is not a blob");
                const auto* data = static_cast<const unsigned char*>(sqlite3_column_blob(st.get(), 3));
                const std::size_t size = static_cast<std::size_t>(sqlite3_column_bytes(st.get(), 3));
                if (size % kEditBytes != 0 || size > kEditBytes * world::kChunkVolume) {
                    throw BadValue("edits blob has " + std::to_string(size) + " bytes, not a whole number of edits");
                }
                std::set<unsigned> seen;
                int bad = 0;
                std::string firstBad;
                for (std::size_t i = 0; i < size; i += kEditBytes) {
                    const unsigned index = data[i] | (unsigned{data[i + 1]} << 8);
                    const unsigned block = data[i + 2];
                    std::string why;
                    if (index >= static_cast<unsigned>(world::kChunkVolume))
                        why = "position index " + std::to_string(index) + " is outside the chunk";
                    else if (block >= static_cast<unsigned>(world::kBlockTypeCount))
                        why = "block id " + std::to_string(block) + " is out of range";
                    else if (!seen.insert(index).second)
                        why = "position index " + std::to_string(index) + " is edited twice";
                    if (!why.empty()) {
                        if (bad++ == 0) firstBad = why;
                        continue;
                    }
                    const int x = static_cast<int>(index) % world::kChunkSize;
                    const int z = static_cast<int>(index) / world::kChunkSize % world::kChunkSize;
                    const int y = static_cast<int>(index) / (world::kChunkSize * world::kChunkSize);
                    s.edits.push_back(
                        {{cx * world::kChunkSize + x, cy * world::kChunkSize + y, cz * world::kChunkSize + z},
                         static_cast<world::BlockType>(block)});
                }
                if (bad > 0) {
                    std::string message = fileName(m_file);
                    message += ": table chunk_edits, row ";
                    message += row;
                    message += ": skipped ";
                    message += std::to_string(bad);
                    message += " bad edit(s) of ";
                    message += std::to_string(size / kEditBytes);
                    message += ": ";
                    message += firstBad;
                    m_warnings.push_back(std::move(message));
                }
            } catch (const BadValue& e) {
                warn("chunk_edits", row, e.what());
            }
        }
    }

    void readPendulums(Snapshot& s) {
        // Slots first, by set.
        struct SlotRows {
            std::array<bool, game::kPendulumSlots> present{};
            PendulumSetRecord rec; // the slots' fields only
        };
        std::map<std::int64_t, SlotRows> slots;
        std::map<std::int64_t, std::string> badSets; // set id -> why
        {
            const Selection q = select("pendulum_slots", {"set_id", "slot"}, slotColumns(), "set_id, slot");
            Stmt st(m_db, m_file, q.sql.c_str());
            while (st.step()) {
                if (sqlite3_column_type(st.get(), 0) != SQLITE_INTEGER) {
                    m_warnings.push_back(fileName(m_file) +
                                         ": table pendulum_slots: skipped a row whose set_id is not an integer");
                    continue;
                }
                const std::int64_t id = sqlite3_column_int64(st.get(), 0);
                try {
                    const auto k = static_cast<std::size_t>(st.intIn(1, "slot", 0, game::kPendulumSlots - 1));
                    SlotRows& rows = slots[id];
                    ColumnReader r{st, q.index};
                    game::visitPendulumSlot(r, rows.rec, k);
                    rows.present[k] = true;
                } catch (const BadValue& e) {
                    badSets.emplace(id, std::string("slot: ") + e.what());
                }
            }
        }
        const Selection q = select("pendulum_sets", {"id"}, setColumns(), "id");
        Stmt st(m_db, m_file, q.sql.c_str());
        while (st.step()) {
            std::string row = "?";
            try {
                const std::int64_t id = st.integer(0, "id");
                row = std::to_string(id);
                std::optional<SlotRows> mine;
                if (const auto f = slots.find(id); f != slots.end()) {
                    mine = f->second;
                    slots.erase(f);
                }
                if (const auto b = badSets.find(id); b != badSets.end()) throw BadValue(b->second);
                for (int i = 0; i < game::kPendulumSlots; ++i) {
                    if (!mine || !mine->present[static_cast<std::size_t>(i)]) {
                        throw BadValue("has no slot " + std::to_string(i) + " (a set has exactly " +
                                       std::to_string(game::kPendulumSlots) + ")");
                    }
                }
                PendulumSetRecord rec = mine->rec;
                ColumnReader r{st, q.index};
                game::visitPendulumSet(r, rec);
                constexpr auto kFar = static_cast<std::int64_t>(game::kWorldBorder); // blocks
                if (rec.base.x < -kFar || rec.base.x >= kFar || rec.base.z < -kFar || rec.base.z >= kFar ||
                    rec.base.y < 0 || rec.base.y >= world::kWorldHeight)
                    throw BadValue("position (" + std::to_string(rec.base.x) + ", " + std::to_string(rec.base.y) +
                                   ", " + std::to_string(rec.base.z) + ") is outside the world");
                // Build it once: the physics' own validation is the last word on what is consistent. Any
                // exception from values in the file (Boost.Math reports its own errors too) makes the
                // record bad; it is skipped with the reason, never allowed to end the game.
                try {
                    game::PendulumSet probe(rec.base, rec.def);
                    probe.restore(rec.internals);
                } catch (const std::exception& e) {
                    throw BadValue(e.what());
                }
                // Where the game would have put it: on a block, not over air.
                const glm::ivec3 below = rec.base - glm::ivec3(0, 1, 0);
                if (!world::isSolid(m_world->get(below)))
                    throw BadValue("it stands over air: the block under it, (" + std::to_string(below.x) + ", " +
                                   std::to_string(below.y) + ", " + std::to_string(below.z) +
                                   "), is not solid (the game places a set on a block)");
                // A slot beyond what the game steps (its own divergence test, or past the physics' bounds on
                // a state) that is not marked diverged would stand frozen: marked, and said.
                for (std::size_t k = 0; k < game::kPendulumSlots; ++k) {
                    const physics::PendulumState st = rec.internals.slots[k].state;
                    if (rec.internals.diverged[k] ||
                        (std::abs(st.theta) <= physics::kMaxInitialAngle && std::abs(st.omega) <= 1e6))
                        continue;
                    rec.internals.diverged[k] = true;
                    m_warnings.push_back(fileName(m_file) + ": table pendulum_slots, set " + row + " slot " +
                                         std::to_string(k) + ": theta " + formatCoordinate(st.theta) + ", omega " +
                                         formatCoordinate(st.omega) +
                                         " is beyond what the game steps: marked diverged");
                }
                s.pendulumSets.push_back(rec);
            } catch (const BadValue& e) {
                warn("pendulum_sets", row, e.what());
            }
        }
        for (const auto& [id, unused] : slots) {
            (void)unused;
            m_warnings.push_back(fileName(m_file) + ": table pendulum_slots: skipped slots of set " +
                                 std::to_string(id) + ", which is not in pendulum_sets");
        }
    }

    void readHairBalls(Snapshot& s) {
        const Selection q = select("hair_balls", {"id"}, ballColumns(), "id");
        Stmt st(m_db, m_file, q.sql.c_str());
        const auto solverColumn = q.index.find("solver"); // v3 added it; a v2 ball was stepped by dftl
        while (st.step()) {
            std::string row = "?";
            try {
                row = std::to_string(st.integer(0, "id"));
                HairBallRecord rec;
                rec.def.hair.method = physics::HairMethod::Dftl;
                if (solverColumn != q.index.end()) {
                    // First, before any value this build might judge out of range: a ball from a newer build
                    // must refuse the load, not be skipped (and then lost at the next save).
                    const std::string name = st.text(solverColumn->second, "solver");
                    if (!physics::hairMethodFromName(name)) {
                        throw RefusedRecord(fileName(m_file) + ": table hair_balls, row " + row + ": solver " +
                                            core::quoteForMessage(name) + " is unknown to this build (it knows " +
                                            physics::hairMethodNames() +
                                            "); the world may come from a newer Minecrappy. Not opened, not changed");
                    }
                }
                ColumnReader r{st, q.index};
                game::visitHairBall(r, rec, rec.hair);
                if (!game::insideBorder(rec.centre)) throw BadValue("centre is outside the world border");
                physics::HairParams& h = rec.def.hair;
                if (h.strands < 1 || h.nodesPerStrand < 2 ||
                    static_cast<std::int64_t>(h.strands) * h.nodesPerStrand > kMaxSavedHairNodes) {
                    throw BadValue("strands x nodes_per_strand = " + std::to_string(h.strands) + " x " +
                                   std::to_string(h.nodesPerStrand) + " is outside 1 x 2 .. " +
                                   std::to_string(kMaxSavedHairNodes) + " nodes");
                }
                // Before v3 every ball carried the then default of 1/30 s (no panel sets it), which made the
                // hair's look and settling follow the tick rate; such a ball gets today's default.
                if (solverColumn == q.index.end() && h.maxSubstepSeconds == 1.0f / 30.0f)
                    h.maxSubstepSeconds = physics::HairParams{}.maxSubstepSeconds;
                try {
                    game::validateHairBallDef(rec.def); // the game's limits, physics::validateHairParams included
                } catch (const std::invalid_argument& e) {
                    throw BadValue(e.what());
                }
                // The hair as it was (v4). Without it, or with one that does not fit the ball, the ball is kept
                // and its hair starts anew from the spawn pose; the load says so.
                const std::string here = fileName(m_file) + ": table hair_balls, row " + row;
                if (r.hairRead == ColumnReader::Hair::Absent) {
                    m_warnings.push_back(here + ": saved before worlds kept the hair (schema " +
                                         std::to_string(m_version) + "): its hair starts anew");
                } else if (r.hairRead == ColumnReader::Hair::Missing) {
                    m_warnings.push_back(here + ": hair_state is missing: its hair starts anew");
                } else {
                    try {
                        physics::HairSolverState hair = decodeHairState(r.hairBlob, h.strands, h.nodesPerStrand);
                        game::HairBall probe(rec.centre, rec.def); // the same checks restore() will meet
                        probe.restoreHair(hair);
                        rec.hair = std::move(hair);
                    } catch (const std::invalid_argument& e) {
                        m_warnings.push_back(here + ": " + e.what() + ": its hair starts anew");
                    }
                }
                // Where the game would have put it: in free space (no block) and apart from the balls before it.
                if (game::sphereOverlapsSolid(*m_world, rec.centre, rec.def.radius))
                    throw BadValue("it is inside blocks (the game places balls in free space)");
                for (std::size_t j = 0; j < s.hairBalls.size(); ++j) {
                    const HairBallRecord& other = s.hairBalls[j];
                    if (glm::distance(other.centre, rec.centre) < other.def.radius + rec.def.radius)
                        throw BadValue("it overlaps the ball of row " + m_ballRows[j] +
                                       " (the game places balls apart)");
                }
                m_ballRows.push_back(row);
                s.hairBalls.push_back(std::move(rec));
            } catch (const BadValue& e) {
                warn("hair_balls", row, e.what());
            }
        }
    }

    int m_version = kSchemaVersion;
    std::optional<world::World> m_world; // the terrain and the edits, from readEdits on
    std::vector<std::string> m_ballRows; // the row of each ball kept so far
    sqlite3* m_db;
    const std::filesystem::path& m_file;
    std::vector<std::string>& m_warnings;
};

// ---- the file as bytes, before SQLite sees it ----------------------------------------------------------

struct Header {
    bool sqlite = false;
    std::uint32_t applicationId = 0;
    std::uint32_t pageSize = 0;
    std::uint32_t pageCount = 0; // valid only when pageCountValid
    bool pageCountValid = false;
};

std::uint32_t be32(const unsigned char* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// The first 100 bytes of a database (fewer: not a database).
Header parseHeader(const unsigned char* b, std::size_t size) {
    Header h;
    if (size < 100 || std::memcmp(b, "SQLite format 3", 16) != 0) return h;
    h.sqlite = true;
    h.pageSize = (unsigned{b[16]} << 8) | b[17];
    if (h.pageSize == 1) h.pageSize = 65536;
    h.applicationId = be32(b + 68);
    h.pageCount = be32(b + 28);
    h.pageCountValid = h.pageCount != 0 && be32(b + 24) == be32(b + 92); // change counter == version-valid-for
    return h;
}

Header readHeader(const std::filesystem::path& file, std::uintmax_t size) {
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(file, "cannot be read (permissions?)");
    unsigned char b[100] = {};
    if (size < sizeof b) return {};
    in.read(reinterpret_cast<char*>(b), sizeof b);
    if (!in) return {};
    return parseHeader(b, sizeof b);
}

std::string hex32(std::uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%08x", v);
    return buf;
}

// Step 1 of open(), on the header: an SQLite database with our application id, and all of it there.
void checkHeader(const std::filesystem::path& file, const Header& h, std::uintmax_t size) {
    if (size == 0) fail(file, "is empty: not a Minecrappy world");
    if (!h.sqlite) fail(file, "is not a Minecrappy world (not an SQLite database)");
    if (h.applicationId != static_cast<std::uint32_t>(kApplicationId)) {
        fail(file, "is not a Minecrappy world (SQLite application id " + hex32(h.applicationId) + ", expected " +
                       hex32(static_cast<std::uint32_t>(kApplicationId)) + ")");
    }
}

void checkComplete(const std::filesystem::path& file, const Header& h, std::uintmax_t size) {
    if (h.pageCountValid && static_cast<std::uintmax_t>(h.pageCount) * h.pageSize > size) {
        fail(file, "is truncated (" + std::to_string(size) + " bytes, its header says " +
                       std::to_string(static_cast<std::uintmax_t>(h.pageCount) * h.pageSize) + ")");
    }
}

void syncDirectory(const std::filesystem::path& dir) {
    const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd >= 0) {
        (void)::fsync(fd);
        ::close(fd);
    }
}

// Read-only by permission bits (what the user asked for, also when running as root) or by access().
bool readOnlyFile(const std::filesystem::path& file) {
    std::error_code ec;
    const auto perms = std::filesystem::status(file, ec).permissions();
    if (!ec && (perms & std::filesystem::perms::owner_write) == std::filesystem::perms::none) return true;
    return ::access(file.c_str(), W_OK) != 0;
}

void setWritePragmas(sqlite3* db, const std::filesystem::path& file) {
    // Rollback journal, not WAL: the file is one self-contained file at rest (copy it, mail it), a read-only
    // connection can validate it without creating -wal/-shm files, and with synchronous=FULL a commit is
    // durable and all-or-nothing.
    exec(db, file, "PRAGMA journal_mode=DELETE; PRAGMA synchronous=FULL; PRAGMA foreign_keys=OFF;");
    sqlite3_busy_timeout(db, 5000);
}

} // namespace

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

// ---- snapshots -------------------------------------------------------------------------------------

Snapshot takeSnapshot(const game::GameState& state) {
    Snapshot s;
    s.terrain = state.world.terrain();
    s.tick = state.tick;
    s.paused = state.paused;
    s.player = state.player;
    s.edits = state.world.edits();
    s.pendulumSets.reserve(state.pendulumSets.size());
    for (const auto& set : state.pendulumSets) s.pendulumSets.push_back({set.base(), set.def(), set.internals()});
    s.hairBalls.reserve(state.hairBalls.size());
    for (const auto& ball : state.hairBalls)
        s.hairBalls.push_back({ball.centre(), ball.spinAngle(), ball.def(), ball.solver().state()});
    // A carried ball is put down where it is: the state that loads is not carrying, so hash it that way
    // (WorldFile.PauseRoundTripsAndACarriedBallIsPutDown checks it against a real reload).
    s.stateHash = game::stateHash(state, /*asPutDown=*/true);
    return s;
}

game::GameState restore(const Snapshot& snap) {
    game::GameDef def;
    def.terrain = snap.terrain;
    def.demoObjects = false;
    game::GameState state(def);
    state.tick = snap.tick;
    state.paused = snap.paused;
    if (!snap.resetPlayer) state.player = snap.player; // else the new state's player, at the spawn point
    state.previousPlayer = state.player;
    for (const auto& e : snap.edits) state.world.set(e.pos, e.block);
    state.pendulumSets.reserve(snap.pendulumSets.size());
    for (const auto& r : snap.pendulumSets) {
        state.pendulumSets.emplace_back(r.base, r.def);
        state.pendulumSets.back().restore(r.internals);
    }
    state.hairBalls.reserve(snap.hairBalls.size());
    for (const auto& r : snap.hairBalls) {
        state.hairBalls.emplace_back(r.centre, r.def);
        if (r.spin != 0.0f) state.hairBalls.back().setSpin(r.spin);
        if (r.hair) state.hairBalls.back().restoreHair(*r.hair);
    }
    return state;
}

// ---- open ------------------------------------------------------------------------------------------

namespace {

void writeSnapshot(sqlite3* db, const std::filesystem::path& file, const Snapshot& snap); // see save()

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

} // namespace

std::unique_ptr<WorldStore> WorldStore::open(const std::filesystem::path& given, bool createIfMissing) {
    // A world path that is a symbolic link is followed once, here, and the link kept: SQLite follows it too
    // and keeps its journal beside the file it leads to, so the hot-journal check, the saves and the
    // read-only check all use that file. A link that leads nowhere (dangling, or a loop) is refused, as for
    // every output (core::resolveOutput): a world is never created at, or in place of, a broken link.
    std::error_code ec;
    std::filesystem::path file = given;
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(given, ec))) {
        file = std::filesystem::canonical(given, ec);
        if (ec) fail(given, "is a symbolic link that leads to no file (" + ec.message() + ")");
    }
    std::unique_ptr<WorldStore> store(new WorldStore(file));
    const auto status = std::filesystem::status(file, ec);
    if (!std::filesystem::exists(status)) {
        if (!createIfMissing) fail(file, "no such world");
        createWorld(file);
    } else if (!std::filesystem::is_regular_file(status)) {
        fail(file, "is not a file");
    }

    // 1. Bytes: is this an SQLite file with our application id, and all of it there?
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec) fail(file, "cannot be read: " + ec.message());
    Header h = size == 0 ? Header{} : readHeader(file, size);
    checkHeader(file, h, size);

    // 2. A save that was killed leaves a hot journal. Rolling it back is SQLite's crash recovery and restores
    // the last completed save; a read-only connection cannot do it, so let a read-write one do just that.
    std::filesystem::path journal = file;
    journal += "-journal";
    if (std::filesystem::exists(journal, ec) && std::filesystem::file_size(journal, ec) > 0) {
        Db db;
        if (sqlite3_open_v2(file.c_str(), &db.h, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
            fail(file, std::string("an interrupted save cannot be rolled back: ") +
                           (db.h ? sqlite3_errmsg(db.h) : "out of memory"));
        }
        const int rc = sqlite3_exec(db.h, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr);
        if (rc != SQLITE_OK)
            fail(file, std::string("an interrupted save cannot be rolled back: ") + sqlite3_errmsg(db.h));
        store->m_warnings.push_back(fileName(file) +
                                    ": an interrupted save was rolled back; the world is as last saved");
        h = readHeader(file, std::filesystem::file_size(file, ec));
    }
    checkComplete(file, h, std::filesystem::file_size(file, ec));

    // 3. Read-only: version, structure, then every record.
    {
        Db db;
        if (sqlite3_open_v2(file.c_str(), &db.h, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
            fail(file, std::string("cannot be opened: ") + (db.h ? sqlite3_errmsg(db.h) : "out of memory"));
        }
        sqlite3_busy_timeout(db.h, 5000);
        store->readValidated(db.h);
    }
    // 4. Writable? Checked now so the game learns it at start, not at the first autosave. A read-only world
    // still loads; save() will say why it cannot write.
    if (readOnlyFile(file)) {
        store->m_warnings.push_back(fileName(file) + ": is read-only; the game cannot be saved to it");
    }
    return store;
}

std::unique_ptr<WorldStore> WorldStore::openImage(std::span<const unsigned char> bytes, const std::string& name) {
    std::unique_ptr<WorldStore> store(new WorldStore(name));
    store->m_inMemory = true;
    const std::filesystem::path& file = store->m_path;
    checkHeader(file, parseHeader(bytes.data(), bytes.size()), bytes.size());
    checkComplete(file, parseHeader(bytes.data(), bytes.size()), bytes.size());
    Db db;
    if (sqlite3_open_v2(":memory:", &db.h, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK)
        fail(file, "cannot be opened: out of memory");
    // SQLite owns (and frees) the copy; read-only, so nothing can grow or change it.
    auto* copy = static_cast<unsigned char*>(sqlite3_malloc64(bytes.size()));
    if (!copy) fail(file, "cannot be opened: out of memory");
    std::memcpy(copy, bytes.data(), bytes.size());
    if (sqlite3_deserialize(db.h, "main", copy, static_cast<sqlite3_int64>(bytes.size()),
                            static_cast<sqlite3_int64>(bytes.size()),
                            SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY) != SQLITE_OK) {
        fail(file, std::string("cannot be opened: ") + sqlite3_errmsg(db.h));
    }
    store->readValidated(db.h);
    return store;
}

std::vector<unsigned char> WorldStore::toImage(const Snapshot& snapshot) {
    const std::filesystem::path file = "(in memory)";
    Db db;
    if (sqlite3_open_v2(":memory:", &db.h, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK)
        fail(file, "cannot create: out of memory");
    std::string sql = "PRAGMA application_id=" + std::to_string(kApplicationId) + "; BEGIN; ";
    sql += currentSchemaSql();
    sql += "PRAGMA user_version=" + std::to_string(kSchemaVersion) + ";";
    exec(db.h, file, sql.c_str());
    writeSnapshot(db.h, file, snapshot);
    exec(db.h, file, "COMMIT");
    sqlite3_int64 size = 0;
    unsigned char* data = sqlite3_serialize(db.h, "main", &size, 0);
    if (!data) fail(file, "cannot serialize: out of memory");
    std::vector<unsigned char> out(data, data + size);
    sqlite3_free(data);
    return out;
}

void WorldStore::readValidated(sqlite3* db) {
    const std::filesystem::path& file = m_path;
    {
        if (pragmaInt(db, file, "PRAGMA application_id") != kApplicationId) fail(file, "is not a Minecrappy world");
        const std::int64_t version = pragmaInt(db, file, "PRAGMA user_version");
        if (version > kSchemaVersion) {
            fail(file, "was written by a newer Minecrappy (world schema version " + std::to_string(version) +
                           "; this build reads up to " + std::to_string(kSchemaVersion) + "); not opened, not changed");
        }
        if (version < 1) fail(file, "is not a Minecrappy world (no schema version)");
        {
            Stmt check(db, file, "PRAGMA quick_check(5)");
            std::string problems;
            while (check.step()) {
                const auto* t = reinterpret_cast<const char*>(sqlite3_column_text(check.get(), 0));
                const std::string line = t ? t : "";
                if (line != "ok") problems += (problems.empty() ? "" : "; ") + line;
            }
            if (!problems.empty()) fail(file, "is damaged (quick_check: " + problems + ")");
        }
        RecordReader reader(db, file, m_warnings);
        m_loaded = reader.read(static_cast<int>(version));
        m_isNew = !m_loaded.has_value();
    }
}

Snapshot WorldStore::load() {
    if (!m_loaded) {
        if (m_isNew) fail(m_path, "holds no saved world yet");
        if (m_inMemory) fail(m_path, "was loaded already (a world in memory is loaded once)");
        // Loaded once already: read it again, with the same validation.
        std::unique_ptr<WorldStore> again = open(m_path, false);
        if (again->m_isNew || !again->m_loaded) fail(m_path, "holds no saved world");
        m_warnings = again->m_warnings;
        return std::move(*again->m_loaded);
    }
    Snapshot s = std::move(*m_loaded);
    m_loaded.reset();
    return s;
}

// ---- save ------------------------------------------------------------------------------------------

namespace {

// Replaces every record with the snapshot's, inside the caller's transaction, then reads them back through
// the loader: what would not load is not saved (the caller rolls back).
void writeSnapshot(sqlite3* db, const std::filesystem::path& file, const Snapshot& snap) {
    std::int64_t saves = 0;
    {
        Stmt st(db, file, "SELECT value FROM meta WHERE key = 'save_count'");
        if (st.step() && sqlite3_column_type(st.get(), 0) == SQLITE_INTEGER) saves = sqlite3_column_int64(st.get(), 0);
    }
    exec(db, file,
         "DELETE FROM meta; DELETE FROM player; DELETE FROM chunk_edits; DELETE FROM pendulum_sets; "
         "DELETE FROM pendulum_slots; DELETE FROM hair_balls;");
    {
        // The state's values (game::visitMeta), one row each, then the save's own.
        Stmt st(db, file, "INSERT INTO meta (key, value) VALUES (?1, ?2)");
        const game::StateMeta meta{snap.tick, snap.terrain.seed, snap.terrain.kind, snap.paused};
        MetaRowWriter rows{st};
        game::visitMeta(rows, meta);
        st.bind(1, std::string("state_hash"));
        st.bind(2, game::hashToHex(snap.stateHash));
        st.run();
        st.bind(1, std::string("save_count"));
        st.bind(2, saves + 1);
        st.run();
    }
    {
        Stmt st(db, file, insertSql("player", {"id"}, playerColumns()).c_str());
        st.bind(1, 0);
        Binder b{st, 2};
        game::visitPlayer(b, snap.player);
        st.run();
    }
    {
        std::map<world::ChunkCoord, std::vector<unsigned char>> chunks;
        for (const auto& e : snap.edits) {
            if (e.pos.y < 0 || e.pos.y >= world::kWorldHeight) continue; // the world ignores these too
            auto& blob = chunks[world::chunkOf(e.pos)];
            const std::uint16_t i = localIndex(world::localOf(e.pos));
            blob.push_back(static_cast<unsigned char>(i & 0xff));
            blob.push_back(static_cast<unsigned char>(i >> 8));
            blob.push_back(static_cast<unsigned char>(e.block));
        }
        Stmt st(db, file, "INSERT INTO chunk_edits (cx, cy, cz, edits) VALUES (?1, ?2, ?3, ?4)");
        for (const auto& [c, blob] : chunks) {
            st.bind(1, c.x);
            st.bind(2, c.y);
            st.bind(3, c.z);
            st.bindBlob(4, blob);
            st.run();
        }
    }
    {
        Stmt set(db, file, insertSql("pendulum_sets", {"id"}, setColumns()).c_str());
        Stmt slot(db, file, insertSql("pendulum_slots", {"set_id", "slot"}, slotColumns()).c_str());
        int id = 0;
        for (const auto& r : snap.pendulumSets) {
            set.bind(1, id);
            Binder b{set, 2};
            game::visitPendulumSet(b, r);
            set.run();
            for (int i = 0; i < game::kPendulumSlots; ++i) {
                slot.bind(1, id);
                slot.bind(2, i);
                Binder s{slot, 3};
                game::visitPendulumSlot(s, r, static_cast<std::size_t>(i));
                slot.run();
            }
            ++id;
        }
    }
    {
        Stmt st(db, file, insertSql("hair_balls", {"id"}, ballColumns()).c_str());
        int id = 0;
        for (const auto& r : snap.hairBalls) {
            st.bind(1, id++);
            Binder b{st, 2};
            game::visitHairBall(b, r, r.hair);
            st.run();
        }
    }
    // Save only what loads: read the transaction back through the loader, on this connection, before
    // committing. A record the loader would skip or reset (a value the game should never have held) fails
    // the save, naming it, and the file keeps its last good save.
    {
        std::vector<std::string> wouldWarn;
        try {
            RecordReader(db, file, wouldWarn).read(kSchemaVersion);
        } catch (const RefusedRecord& e) { // a record that refuses the whole load (an unknown solver)
            fail(file, std::string("cannot save: the loader would refuse it: ") + e.what());
        }
        if (!wouldWarn.empty()) fail(file, "cannot save: the loader would refuse it: " + wouldWarn.front());
    }
}

} // namespace

void WorldStore::save(const Snapshot& snap) {
    const std::lock_guard lock(m_saveMutex);
    const std::filesystem::path& file = m_path;
    if (m_inMemory) fail(file, "cannot save: a world opened from memory has no file (use toImage)");
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) fail(file, "cannot save: the world file is gone (deleted or moved?)");
    if (readOnlyFile(file)) fail(file, "cannot save: the world file is read-only");
    Db db;
    // No SQLITE_OPEN_CREATE: a world deleted under us is an error, not a fresh empty file.
    if (sqlite3_open_v2(file.c_str(), &db.h, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
        fail(file, std::string("cannot save: ") + (db.h ? sqlite3_errmsg(db.h) : "out of memory"));
    }
    if (sqlite3_db_readonly(db.h, "main") == 1) fail(file, "cannot save: the world file is read-only");
    setWritePragmas(db.h, file);
    exec(db.h, file, "BEGIN IMMEDIATE");
    try {
        // Still our world, at a version this build knows? (The file may have been replaced since open.)
        if (pragmaInt(db.h, file, "PRAGMA application_id") != kApplicationId)
            fail(file, "cannot save: no longer a Minecrappy world");
        std::int64_t version = pragmaInt(db.h, file, "PRAGMA user_version");
        if (version > kSchemaVersion || version < 1)
            fail(file, "cannot save: unexpected schema version " + std::to_string(version));
        for (; version < kSchemaVersion; ++version) exec(db.h, file, kMigrations.at(static_cast<int>(version)));
        exec(db.h, file, ("PRAGMA user_version=" + std::to_string(kSchemaVersion)).c_str());

        writeSnapshot(db.h, file, snap);
        exec(db.h, file, "COMMIT");
    } catch (...) {
        sqlite3_exec(db.h, "ROLLBACK", nullptr, nullptr, nullptr);
        throw;
    }
}

void removeWorldFiles(const std::filesystem::path& file, std::error_code& ec) {
    std::filesystem::remove(file, ec);
    for (const char* suffix : {"-journal", "-wal", "-shm"}) {
        std::error_code sidecar;
        std::filesystem::remove(file.string() + suffix, sidecar);
        if (sidecar && !ec) ec = sidecar;
    }
}

} // namespace save
