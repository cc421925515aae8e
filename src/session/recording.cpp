#include "session/recording.h"

#include <algorithm>
#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <vector>

#include "core/quote.h"
#include "game/command_text.h"
#include "input/script.h"
#include "session/setting_table.h"
#include "session/settings.h"

namespace session {

namespace {

std::string hex(std::uint64_t v) {
    char buffer[20];
    std::snprintf(buffer, sizeof buffer, "%016" PRIx64, v);
    return buffer;
}

template <typename T>
bool parse(std::string_view text, T& out, int base = 10) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out, base);
    return ec == std::errc{} && end == text.data() + text.size();
}

std::string joined(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) {
        out += ' ';
        out += w;
    }
    return out;
}

} // namespace

bool isRecording(std::string_view text) { return text.substr(0, kRecordingMagic.size()) == kRecordingMagic; }

int compareVersions(std::string_view a, std::string_view b) {
    while (!a.empty() || !b.empty()) {
        const auto next = [](std::string_view& s) {
            const std::size_t dot = s.find('.');
            std::uint64_t n = 0;
            parse(s.substr(0, dot), n);
            s = dot == std::string_view::npos ? std::string_view() : s.substr(dot + 1);
            return n;
        };
        const std::uint64_t x = next(a), y = next(b);
        if (x != y) return x < y ? -1 : 1;
    }
    return 0;
}

Recording parseRecording(std::string_view text, std::string_view fileName) {
    Recording r;
    bool ended = false;
    int line = 0;
    for (std::string_view row : core::splitAt(text, '\n')) {
        ++line;
        if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
        if (row.substr(0, 2) != "# ") continue; // events, and other comments
        const auto fail = [&](const std::string& why) -> void {
            throw input::ScriptError(std::string(fileName) + ":" + std::to_string(line) + ": " + why);
        };
        std::string_view rest = row.substr(2);
        const std::size_t space = rest.find(' ');
        const std::string_view key = rest.substr(0, space);
        const std::string_view value = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
        if (ended) fail("a recording ends at its '# end' line; this line follows it");
        bool ok = true;
        if (key == "minecrappy") {
            ok = line == 1 && value.substr(0, 10) == "recording " && parse(value.substr(10), r.header.format);
            if (ok && r.header.format < kRecordingFormat)
                fail("recording format " + std::to_string(r.header.format) +
                     " was made before the day clock: its state hashes leave out the time of day, so this game "
                     "(format " +
                     std::to_string(kRecordingFormat) + ") cannot replay it");
            if (ok && r.header.format > kRecordingFormat)
                fail("recording format " + std::to_string(r.header.format) + " (this game reads format " +
                     std::to_string(kRecordingFormat) + ")");
        } else if (key == "version") {
            // A release number: one to three numbers between dots (session::startReplay refuses a newer one).
            std::uint64_t part = 0;
            int parts = 0;
            for (const std::string_view p : core::splitAt(value, '.')) ok = ok && parse(p, part) && ++parts <= 3;
            ok = ok && parts >= 1;
            if (!ok) fail("version '" + std::string(value) + "' is not a Minecrappy release number (like 0.1.0)");
            r.header.version = std::string(value);
        } else if (key == "seed") {
            ok = parse(value, r.header.seed);
        } else if (key == "terrain") {
            r.header.terrain = std::string(value);
        } else if (const SettingRow* row = findSetting(key); row && row->simulation) {
            // The settings that change the simulation, as the settings file writes them.
            if (const std::string problem = parseSetting(*row, value, r.header.settings); !problem.empty())
                fail(std::string(key) + " " + std::string(value) + ": " + problem);
        } else if (key == "start_world") {
            r.header.startWorld = std::string(value);
            ok = !value.empty() && value.find('/') == std::string_view::npos;
        } else if (key == "start_tick") {
            ok = parse(value, r.header.startTick);
        } else if (key == "hash_every") {
            ok = parse(value, r.header.hashEvery) && r.header.hashEvery > 0;
        } else if (key == "hash") {
            const std::size_t sp = value.find(' ');
            std::uint64_t tick = 0, hash = 0;
            ok = sp != std::string_view::npos && parse(value.substr(0, sp), tick) && value.size() - sp - 1 == 16 &&
                 parse(value.substr(sp + 1), hash, 16);
            if (ok && !r.hashes.emplace(tick, hash).second)
                fail("a second hash of tick " + std::to_string(tick) + "; a recording has one for each");
        } else if (key == "end") {
            ok = parse(value, r.endTick);
            ended = true;
        } else {
            continue; // a comment someone added
        }
        if (!ok) fail("malformed recording line '" + std::string(row) + "'");
        if (key == "hash") continue;
        // A header key given twice: which one the recorder wrote cannot be told, so neither is taken.
        if (const auto first = r.headerLines.find(key); first != r.headerLines.end())
            fail("'# " + std::string(key) + "' is given a second time (first at line " + std::to_string(first->second) +
                 "); a recording's header holds each key once");
        r.headerLines.emplace(key, line);
    }
    const auto fail = [&](const std::string& why) { throw input::ScriptError(std::string(fileName) + ": " + why); };
    if (!isRecording(text)) fail("not a recording (its first line is not '# minecrappy recording N')");
    std::vector<std::string_view> required = {"version", "seed", "terrain", "start_world", "start_tick"};
    for (const SettingRow& row : kSettingRows)
        if (row.simulation) required.push_back(row.key);
    for (const std::string_view key : required) {
        if (!r.headerLines.count(key)) fail("the header has no '# " + std::string(key) + "' line");
    }
    if (!ended) fail("the recording was cut short: it has no '# end' line");
    if (!r.hashes.count(r.header.startTick)) fail("the recording has no hash of its start state");
    return r;
}

namespace {

// The start world an existing recording at `resolved` names (an empty path when there is none, the file is not a
// recording, or the name is not a plain file name in its folder): what to remove once a new recording replaces it.
std::filesystem::path startWorldOf(const std::filesystem::path& resolved) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(resolved, ec)) return {};
    std::ifstream in(resolved);
    std::string line;
    if (!std::getline(in, line) || !isRecording(line)) return {};
    constexpr std::string_view kKey = "# start_world ";
    for (int n = 0; n < 64 && std::getline(in, line); ++n) { // the header is at the top
        if (!line.starts_with(kKey)) continue;
        const std::filesystem::path name = line.substr(kKey.size());
        if (name.empty() || name != name.filename() || name == "." || name == "..") return {};
        return resolved.parent_path() / name;
    }
    return {};
}

// A start-world name beside `resolved` that nothing holds yet: FILE.start.mcworld, else FILE.start.2.mcworld, ...
std::filesystem::path freshStartWorld(const std::filesystem::path& resolved) {
    const std::string stem = resolved.string() + ".start";
    for (int n = 1;; ++n) {
        std::filesystem::path candidate = n == 1 ? stem + ".mcworld" : stem + "." + std::to_string(n) + ".mcworld";
        std::error_code ec;
        if (!std::filesystem::exists(std::filesystem::symlink_status(candidate, ec))) return candidate;
    }
}

} // namespace

Recorder::Recorder(const std::filesystem::path& path, RecordingHeader header, const save::Snapshot& start,
                   std::uint64_t startHash)
    : m_path(path), m_hashEvery(header.hashEvery), m_startTick(header.startTick) {
    // The start world lies beside the file the path leads to, which must be a file: a pipe or a device has no
    // folder to hold it (and /dev/stdout's would be /dev/stdout.start.mcworld).
    const core::OutputPath out = core::resolveOutput(path);
    if (out.kind == core::OutputPath::Kind::InPlace)
        throw core::OutputError("cannot write '" + path.string() +
                                "': a recording is a file with its start world beside it, not a pipe or a device");
    // The old recording and its start world stay a pair until the new recording replaces the old file: the new
    // start world takes a name nothing holds, and the old one is removed only after (finish()), so a session
    // killed at any moment leaves the old recording replayable and at worst an unused start world.
    m_oldStartWorld = startWorldOf(out.resolved);
    m_startWorld = freshStartWorld(out.resolved);
    if (m_oldStartWorld == m_startWorld) m_oldStartWorld.clear();
    header.startWorld = m_startWorld.filename().string();
    const std::vector<unsigned char> image = save::WorldStore::toImage(start);
    core::writeOutput(m_startWorld, {reinterpret_cast<const char*>(image.data()), image.size()});
    m_out.emplace(path);
    std::ostream& o = m_out->stream();
    o << kRecordingMagic << header.format << "\n"
      << "# version " << header.version << "\n"
      << "# seed " << header.seed << "\n"
      << "# terrain " << header.terrain << "\n";
    for (const SettingRow& row : kSettingRows)
        if (row.simulation) o << "# " << row.key << " " << settingText(row, header.settings) << "\n";
    o << "# start_world " << header.startWorld << "\n"
      << "# start_tick " << header.startTick << "\n"
      << "# hash_every " << header.hashEvery << "\n"
      << "# hash " << header.startTick << " " << hex(startHash) << "\n";
}

void Recorder::beforeTick(std::uint64_t tick, const input::Actions& actions, const game::TickCommands& commands) {
    if (m_finished) return;
    std::ostream& o = m_out->stream();
    if (const std::string words = input::actWords(actions); !words.empty()) o << tick << " act " << words << "\n";
    for (const auto& c : commands.pendulum)
        o << tick << " pendulum " << c.set << joined(game::pendulumCommandWords(c)) << "\n";
    for (const auto& c : commands.hair) o << tick << " hair " << c.ball << joined(game::hairCommandWords(c)) << "\n";
    if (commands.timeOfDay) o << tick << " time " << game::exactHours(*commands.timeOfDay) << "\n";
    for (const auto& c : commands.hotbar)
        o << tick << " hotbar " << c.slot + 1 << " " << game::itemName(c.item) << "\n";
}

void Recorder::afterTick(std::uint64_t tick, std::uint64_t hash) {
    if (m_finished || tick % m_hashEvery != 0) return;
    m_out->stream() << "# hash " << tick << " " << hex(hash) << "\n";
}

void Recorder::finish(std::uint64_t endTick) {
    if (m_finished) return;
    m_finished = true;
    m_out->stream() << "# end " << endTick << "\n";
    std::error_code ec;
    try {
        m_out->commit();
    } catch (const core::OutputError&) {
        // The old recording is as it was and still names its own start world: this session's is nobody's.
        std::filesystem::remove(m_startWorld, ec);
        throw;
    }
    if (!m_oldStartWorld.empty()) std::filesystem::remove(m_oldStartWorld, ec); // no recording names it now
}

} // namespace session
