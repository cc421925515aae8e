// Loading: open() and openImage() check a world's bytes (header, application id, a complete file, an
// interrupted save rolled back), then readValidated() its version and quick_check, and RecordReader reads every
// table into the Snapshot that load() hands out. Each record is decoded here, column by column and checked for
// its type; whether its values can be trusted is record_checks.cpp's.
#include "save/store_internal.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>
#include <type_traits>

#include "game/hair_ball.h"
#include "world/chunk.h"

namespace save {

namespace {

// ---- items -------------------------------------------------------------------------------------------

// The default hotbar of the builds before the lamp (schema 4 and older): today's with the log in slot 6.
std::array<game::Item, game::kHotbarSize> preLampHotbar() {
    std::array<game::Item, game::kHotbarSize> h = game::Player{}.hotbar;
    for (game::Item& item : h)
        if (item == game::Item::ofBlock(world::BlockType::Lamp)) item = game::Item::ofBlock(world::BlockType::Log);
    return h;
}

// Reads a record's fields from a row by column name, each checked for its type (BadValue naming the column).
// A listed column the query lacks (a later schema added it; see RecordReader::select) leaves the field's default.
struct ColumnReader {
    const Stmt& st;
    const std::map<std::string, int>& index;
    // The hair blob: no column (an older schema), NULL, or its bytes.
    enum class Hair { Absent, Missing, Present } hairRead = Hair::Absent;
    std::vector<unsigned char> hairBlob{};
    // The file's schema: a hotbar naming a block a later schema brought is no item of this file.
    int version = kSchemaVersion;

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
            const auto parsed = game::itemFromName(itemText);
            if (!parsed) throw BadValue("hotbar item '" + itemText + "' is unknown");
            if (parsed->kind == game::ItemKind::Block && static_cast<int>(parsed->block) >= blockIdsOfSchema(version))
                throw BadValue("hotbar item '" + itemText + "' came in a later schema than this file's (" +
                               std::to_string(version) + ")");
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

} // namespace

// ---- reading -----------------------------------------------------------------------------------------

std::optional<Snapshot> RecordReader::read(int version) {
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

void RecordReader::warn(const char* table, const std::string& row, const std::string& why) {
    m_warnings.push_back(fileName(m_file) + ": table " + table + ", row " + row + ": skipped: " + why);
}

RecordReader::Selection RecordReader::select(const char* table, std::initializer_list<const char*> keys,
                                             const std::vector<std::string>& listed, const char* orderBy) {
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

bool RecordReader::readMeta(Snapshot& s) {
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
            if (!st.step()) {
                if (m_version < 5 && game::isDayClockKey(key)) continue; // before the clock: the default day
                fail(m_file, "bad world settings (table meta): no '" + key + "'");
            }
            const std::map<std::string, int> index{{key, 0}}; // this key's value; the others' are absent
            ColumnReader r{st, index};
            game::visitMeta(r, meta);
        }
        checkMeta(meta);
        s.tick = meta.tick;
        s.terrain.seed = meta.seed;
        s.terrain.kind = meta.terrain;
        s.paused = meta.paused;
        s.day = meta.day;
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
void RecordReader::readPlayer(Snapshot& s) {
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
        r.version = m_version;
        game::visitPlayer(r, p);
        checkPlayer(p);
        if (st.step()) throw BadValue("there is more than one row");
    } catch (const BadValue& e) {
        m_warnings.push_back(fileName(m_file) + ": table player, row 0: reset to the spawn point: " + e.what());
        s.resetPlayer = true;
        return;
    }
    placePlayer(p);
    // A world saved before the lamp (schema 4 or older) with the hotbar it began with, never changed: no lamp is
    // anywhere in it to pick, so it gets today's default hotbar, which holds the lamp where the log was.
    if (m_version < 5 && p.hotbar == preLampHotbar()) {
        p.hotbar = game::Player{}.hotbar;
        m_warnings.push_back(fileName(m_file) +
                             ": table player, row 0: the hotbar is the default of a build before the "
                             "lamp: slot 6 holds the lamp now, not the log (logs are picked from trees)");
    }
    s.player = p;
}

void RecordReader::readEdits(Snapshot& s) {
    Stmt st(m_db, m_file, "SELECT cx, cy, cz, edits FROM chunk_edits ORDER BY cx, cy, cz");
    while (st.step()) {
        std::string row = "?";
        try {
            // Chunks past the world border (game/space.h) hold nothing a player can reach.
            constexpr std::int64_t kFarChunk = static_cast<std::int64_t>(game::kWorldBorder) / world::kChunkSize + 1;
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
                const std::string why = editProblem(index, block, seen);
                if (!why.empty()) {
                    if (bad++ == 0) firstBad = why;
                    continue;
                }
                const int x = static_cast<int>(index) % world::kChunkSize;
                const int z = static_cast<int>(index) / world::kChunkSize % world::kChunkSize;
                const int y = static_cast<int>(index) / (world::kChunkSize * world::kChunkSize);
                s.edits.push_back({{cx * world::kChunkSize + x, cy * world::kChunkSize + y, cz * world::kChunkSize + z},
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

void RecordReader::readPendulums(Snapshot& s) {
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
            checkPendulumSet(rec, row);
            s.pendulumSets.push_back(rec);
        } catch (const BadValue& e) {
            warn("pendulum_sets", row, e.what());
        }
    }
    for (const auto& [id, unused] : slots) {
        (void)unused;
        m_warnings.push_back(fileName(m_file) + ": table pendulum_slots: skipped slots of set " + std::to_string(id) +
                             ", which is not in pendulum_sets");
    }
}

void RecordReader::readHairBalls(Snapshot& s) {
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
                checkSolver(name, row);
            }
            ColumnReader r{st, q.index};
            game::visitHairBall(r, rec, rec.hair);
            physics::HairParams& h = rec.def.hair;
            // Before v3 every ball carried the then default of 1/30 s (no panel sets it), which made the
            // hair's look and settling follow the tick rate; such a ball gets today's default.
            if (solverColumn == q.index.end() && h.maxSubstepSeconds == 1.0f / 30.0f)
                h.maxSubstepSeconds = physics::HairParams{}.maxSubstepSeconds;
            checkHairBall(rec); // the world border, the node count, the game's limits
            // The hair as it was (v4). Without it, or with one that does not fit the ball, the ball is kept
            // and its hair starts anew from the spawn pose; the load says so.
            const std::string here = fileName(m_file) + ": table hair_balls, row " + row;
            if (r.hairRead == ColumnReader::Hair::Absent) {
                m_warnings.push_back(here + ": saved before worlds kept the hair (schema " + std::to_string(m_version) +
                                     "): its hair starts anew");
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
            checkHairBallPlace(rec, s);
            m_ballRows.push_back(row);
            s.hairBalls.push_back(std::move(rec));
        } catch (const BadValue& e) {
            warn("hair_balls", row, e.what());
        }
    }
}

// ---- open ------------------------------------------------------------------------------------------

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

} // namespace save
