// Saving: save() writes a Snapshot into its file in one transaction (migrating an older schema first), and
// toImage() into the bytes of a new file. Each table's rows are bound from game/state_fields.h's lists
// (Binder); before the transaction commits, writeSnapshot reads it back through the loader, so what would not
// load is not saved.
#include "save/store_internal.h"

#include <array>
#include <mutex>
#include <type_traits>

#include <unistd.h>

#include "game/state_io.h"
#include "world/chunk.h"

namespace save {

namespace {

// A block's place in its chunk's edits blob (the blob's layout: store_internal.h, kEditBytes).
std::uint16_t localIndex(glm::ivec3 local) {
    return static_cast<std::uint16_t>(local.x + world::kChunkSize * (local.z + world::kChunkSize * local.y));
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
        const game::StateMeta meta{snap.tick, snap.terrain.seed, snap.terrain.kind, snap.paused, snap.day};
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
        const std::int64_t version = pragmaInt(db.h, file, "PRAGMA user_version");
        if (version > kSchemaVersion || version < 1)
            fail(file, "cannot save: unexpected schema version " + std::to_string(version));
        migrateToCurrent(db.h, file, version);

        writeSnapshot(db.h, file, snap);
        exec(db.h, file, "COMMIT");
    } catch (...) {
        sqlite3_exec(db.h, "ROLLBACK", nullptr, nullptr, nullptr);
        throw;
    }
}

} // namespace save
