#include "session/keyframe_file.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/atomic_file.h"
#include "core/hash.h"
#include "game/item.h"
#include "game/state_fields.h"
#include "game/state_io.h"
#include "save/world_store.h"
#include "session/recording.h"

namespace session {

namespace {

static_assert(std::endian::native == std::endian::little, "keyframe files are written in the machine's byte order");

// Why a payload cannot be read; the reader turns it into a warning naming the keyframe.
class Damaged : public std::runtime_error {
    using runtime_error::runtime_error;
};

struct Out {
    std::string& s;
    template <class T>
    void put(T v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const std::size_t at = s.size();
        s.resize(at + sizeof v);
        std::memcpy(s.data() + at, &v, sizeof v);
    }
    void floats(const std::vector<float>& a) {
        put(static_cast<std::uint64_t>(a.size()));
        const std::size_t at = s.size();
        s.resize(at + a.size() * sizeof(float));
        if (!a.empty()) std::memcpy(s.data() + at, a.data(), a.size() * sizeof(float));
    }
};

struct In {
    const char* p;
    std::size_t left;
    template <class T>
    T get(const char* what) {
        if (left < sizeof(T)) throw Damaged(std::string("cut short at ") + what);
        T v;
        std::memcpy(&v, p, sizeof v);
        p += sizeof v;
        left -= sizeof v;
        return v;
    }
    std::uint64_t count(const char* what, std::uint64_t most) {
        const auto n = get<std::uint64_t>(what);
        if (n > most)
            throw Damaged(std::string(what) + " count " + std::to_string(n) + " is beyond " + std::to_string(most));
        return n;
    }
    void floats(std::vector<float>& a, const char* what, std::uint64_t most) {
        const std::uint64_t n = count(what, most);
        if (left < n * sizeof(float)) throw Damaged(std::string("cut short in ") + what);
        a.resize(n);
        if (n > 0) std::memcpy(a.data(), p, n * sizeof(float));
        p += n * sizeof(float);
        left -= n * sizeof(float);
    }
};

template <class T>
bool validEnum(T v) {
    return !game::enumName(v).empty();
}

// The field lists of game/state_fields.h, value by value: bools as a byte 0 or 1, enums by their number, vectors
// by component, a ball's hair as the world file's hair blob.
struct FieldWriter {
    Out& o;
    template <class T>
    void value(const char* /*name*/, const T& x) {
        if constexpr (std::is_same_v<T, bool>) {
            o.put(static_cast<std::uint8_t>(x ? 1 : 0));
        } else if constexpr (std::is_enum_v<T>) {
            o.put(static_cast<std::int32_t>(x));
        } else if constexpr (std::is_arithmetic_v<T>) {
            o.put(x);
        } else {
            for (decltype(T::length()) i = 0; i < T::length(); ++i) o.put(x[i]);
        }
    }
    template <class T>
    void vec(const char* name, const T& x, game::Columns /*columns*/) {
        value(name, x);
    }
    void hotbar(const char* /*name*/, const std::array<game::Item, game::kHotbarSize>& items) {
        for (const game::Item& item : items) {
            o.put(static_cast<std::uint8_t>(item.kind));
            o.put(static_cast<std::uint8_t>(item.block));
        }
    }
    void hair(const char* /*name*/, const physics::HairSolverState& hair, int strands, int nodes) {
        const std::vector<unsigned char> blob = save::encodeHairState(hair, strands, nodes);
        o.put(static_cast<std::uint64_t>(blob.size()));
        o.s.append(reinterpret_cast<const char*>(blob.data()), blob.size());
    }
};

struct FieldReader {
    In& in;
    template <class T>
    void value(const char* name, T& x) {
        if constexpr (std::is_same_v<T, bool>) {
            const auto b = in.get<std::uint8_t>(name);
            if (b > 1) throw Damaged(std::string(name) + " is " + std::to_string(b) + ", not a bool");
            x = b != 0;
        } else if constexpr (std::is_enum_v<T>) {
            x = static_cast<T>(in.get<std::int32_t>(name));
            if (!validEnum(x)) throw Damaged(std::string(name) + " is no value of its kind");
        } else if constexpr (std::is_arithmetic_v<T>) {
            x = in.get<T>(name);
        } else {
            for (decltype(T::length()) i = 0; i < T::length(); ++i) x[i] = in.get<typename T::value_type>(name);
        }
    }
    template <class T>
    void vec(const char* name, T& x, game::Columns /*columns*/) {
        value(name, x);
    }
    void hotbar(const char* name, std::array<game::Item, game::kHotbarSize>& items) {
        for (game::Item& item : items) {
            const auto kind = in.get<std::uint8_t>(name), block = in.get<std::uint8_t>(name);
            if (kind >= static_cast<std::uint8_t>(game::ItemKind::Count) || block >= world::kBlockTypeCount)
                throw Damaged(std::string(name) + " holds no item");
            item = {static_cast<game::ItemKind>(kind), static_cast<world::BlockType>(block)};
            if (!game::isHoldable(item)) throw Damaged(std::string(name) + " holds air"); // checkInvariants's rule
        }
    }
    void hair(const char* name, physics::HairSolverState& hair, int strands, int nodes) {
        const std::uint64_t n = in.count(name, in.left);
        // The sizes before the blob is read: its node arrays are strands x nodes long.
        if (strands < 1 || nodes < 2 || std::int64_t{strands} * nodes > save::kMaxSavedHairNodes)
            throw Damaged("a ball of " + std::to_string(strands) + " x " + std::to_string(nodes) + " hair nodes");
        try {
            hair = save::decodeHairState(
                std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(in.p), n), strands, nodes);
        } catch (const std::invalid_argument& e) {
            throw Damaged(e.what());
        }
        in.p += n;
        in.left -= n;
    }
};

void writeTrace(Out& o, const game::PendulumTrace& t) {
    o.floats(t.time);
    o.floats(t.exactTheta);
    for (const auto& v : t.theta) o.floats(v);
    for (const auto& v : t.energyError) o.floats(v);
    o.put(static_cast<std::uint64_t>(t.head));
    o.put(static_cast<std::uint64_t>(t.size));
}

game::PendulumTrace readTrace(In& in) {
    constexpr std::uint64_t n = game::PendulumTrace::kSamples;
    game::PendulumTrace t;
    in.floats(t.time, "trace", n);
    in.floats(t.exactTheta, "trace", n);
    for (auto& v : t.theta) in.floats(v, "trace", n);
    for (auto& v : t.energyError) in.floats(v, "trace", n);
    t.head = in.count("trace head", n);
    t.size = in.count("trace size", n);
    return t;
}

void writeStats(Out& o, const physics::HairStepStats& s) {
    o.put(s.maxSegmentError), o.put(s.maxPenetration), o.put(static_cast<std::uint8_t>(s.nan ? 1 : 0));
    o.put(s.maxNodeMove), o.put(s.restWindowMove), o.put(static_cast<std::int32_t>(s.substeps));
}

physics::HairStepStats readStats(In& in) {
    physics::HairStepStats s;
    FieldReader r{in};
    r.value("stats", s.maxSegmentError), r.value("stats", s.maxPenetration), r.value("stats", s.nan);
    r.value("stats", s.maxNodeMove), r.value("stats", s.restWindowMove), r.value("stats", s.substeps);
    return s;
}

using BallKey = std::pair<std::uint64_t, std::uint64_t>; // a ball's serial and generation, as the file has them
// What the file's balls became in this process: serials mean something only within the process that wrote them, so
// each serial of the file is given a new one (game::newBallSerial), the same for every keyframe of the file.
struct BallMap {
    std::map<BallKey, std::shared_ptr<const game::HairBallImage>> images;
    std::map<std::uint64_t, std::uint64_t> serials;
    std::uint64_t serialOf(std::uint64_t fileSerial) {
        const auto [it, added] = serials.emplace(fileSerial, 0);
        if (added) it->second = game::newBallSerial();
        return it->second;
    }
};

// The payload: what game::StateImage holds but its def (the session's) and the world's identity.
template <class InEarlier>
void encodeImage(const game::StateImage& image, InEarlier&& inEarlier, std::string& bytes) {
    Out o{bytes};
    FieldWriter w{o};
    o.put(image.tick);
    w.value("paused", image.paused);
    w.value("hours", image.day.hours), w.value("day", image.day.dayMinutes), w.value("stopped", image.day.stopped);
    game::visitPlayer(w, image.player);
    game::visitPlayer(w, image.previousPlayer);
    o.put(static_cast<std::uint64_t>(image.pendulumSets.size()));
    for (const game::PendulumSet& set : image.pendulumSets) {
        const game::PendulumSetRecord r = game::recordOf(set);
        game::visitPendulumSet(w, r);
        for (std::size_t k = 0; k < game::kPendulumSlots; ++k) {
            game::visitPendulumSlot(w, r, k);
            const auto counts = r.internals.slots[k].counts.value_or(physics::Pendulum::Internals::Counts{});
            o.put(counts.evaluations), o.put(counts.dopri5.accepted), o.put(counts.dopri5.rejected);
            o.put(counts.dopri5.evaluations);
        }
        writeTrace(o, set.trace());
    }
    o.put(static_cast<std::uint64_t>(image.hairBalls.size()));
    for (const game::StateImage::Ball& b : image.hairBalls) {
        o.put(b.serial), o.put(b.generation);
        const bool shared = inEarlier(b.serial, b.generation);
        w.value("shared", shared);
        if (shared) continue;
        const game::HairBallImage& ball = *b.image;
        game::HairBallRecord r{ball.centre, ball.spin, ball.def, {}};
        game::visitHairBall(w, r, ball.hair);
        w.vec("previous_centre", ball.previousCentre, {});
        writeStats(o, ball.stats);
    }
    w.value("carried", image.carriedBall.has_value());
    o.put(static_cast<std::uint64_t>(image.carriedBall.value_or(0)));
    o.put(image.tickSeconds);
    o.put(static_cast<std::uint64_t>(image.edits->size()));
    for (const world::BlockEdit& e : *image.edits) {
        o.put(e.pos.x), o.put(e.pos.y), o.put(e.pos.z), o.put(static_cast<std::uint8_t>(e.block));
    }
}

game::StateImage decodeImage(std::string_view bytes, const game::GameDef& def, BallMap& balls) {
    In in{bytes.data(), bytes.size()};
    FieldReader r{in};
    game::StateImage image;
    image.def = def;
    image.tick = in.get<std::uint64_t>("tick");
    r.value("paused", image.paused);
    r.value("hours", image.day.hours), r.value("day", image.day.dayMinutes), r.value("stopped", image.day.stopped);
    game::visitPlayer(r, image.player);
    game::visitPlayer(r, image.previousPlayer);
    const std::uint64_t sets = in.count("pendulum set", in.left / 64); // a set takes far more bytes than 64
    for (std::uint64_t i = 0; i < sets; ++i) {
        game::PendulumSetRecord rec;
        game::visitPendulumSet(r, rec);
        for (std::size_t k = 0; k < game::kPendulumSlots; ++k) {
            game::visitPendulumSlot(r, rec, k);
            physics::Pendulum::Internals::Counts counts;
            r.value("evaluations", counts.evaluations), r.value("accepted", counts.dopri5.accepted);
            r.value("rejected", counts.dopri5.rejected), r.value("evaluations", counts.dopri5.evaluations);
            rec.internals.slots[k].counts = counts;
        }
        game::PendulumTrace trace = readTrace(in);
        try {
            game::PendulumSet set(rec.base, rec.def);
            set.restore(rec.internals);
            set.restoreTrace(std::move(trace));
            image.pendulumSets.push_back(std::move(set));
        } catch (const std::invalid_argument& e) {
            throw Damaged(std::string("pendulum set ") + std::to_string(i + 1) + ": " + e.what());
        }
    }
    const std::uint64_t n = in.count("hair ball", in.left / 17); // at least its serial, generation and flag
    std::vector<BallKey> keys;
    for (std::uint64_t i = 0; i < n; ++i) {
        game::StateImage::Ball b;
        const auto fileSerial = in.get<std::uint64_t>("ball serial");
        b.generation = in.get<std::uint64_t>("ball generation");
        b.serial = balls.serialOf(fileSerial);
        bool shared = false;
        r.value("shared", shared);
        if (shared) {
            const auto it = balls.images.find({fileSerial, b.generation});
            if (it == balls.images.end())
                throw Damaged("hair ball " + std::to_string(i + 1) + " refers to an earlier keyframe's, which is lost");
            b.image = it->second;
        } else {
            game::HairBallRecord rec;
            rec.hair.emplace();
            game::visitHairBall(r, rec, *rec.hair);
            auto ball = std::make_shared<game::HairBallImage>();
            ball->def = rec.def;
            ball->centre = rec.centre;
            ball->spin = rec.spin;
            ball->hair = std::move(*rec.hair);
            r.vec("previous_centre", ball->previousCentre, {});
            ball->stats = readStats(in);
            try {
                (void)game::HairBall(*ball, b.serial,
                                     b.generation); // the checks a ball made from it passes (its def, its hair's sizes)
            } catch (const std::invalid_argument& e) {
                throw Damaged("hair ball " + std::to_string(i + 1) + ": " + e.what());
            }
            b.image = std::move(ball);
        }
        keys.emplace_back(fileSerial, b.generation);
        image.hairBalls.push_back(std::move(b));
    }
    bool carried = false;
    r.value("carried", carried);
    const auto carriedIndex = in.get<std::uint64_t>("carried ball");
    if (carried) {
        if (carriedIndex >= image.hairBalls.size()) throw Damaged("the carried ball is not one of its balls");
        image.carriedBall = static_cast<std::size_t>(carriedIndex);
    }
    image.tickSeconds = in.get<double>("tick length");
    const std::uint64_t edits = in.count("edit", in.left / 13);
    auto list = std::make_shared<std::vector<world::BlockEdit>>();
    list->reserve(edits);
    for (std::uint64_t i = 0; i < edits; ++i) {
        world::BlockEdit e{};
        e.pos.x = in.get<std::int32_t>("edit"), e.pos.y = in.get<std::int32_t>("edit");
        e.pos.z = in.get<std::int32_t>("edit");
        const auto block = in.get<std::uint8_t>("edit");
        if (block >= world::kBlockTypeCount) throw Damaged("an edit holds no block");
        e.block = static_cast<world::BlockType>(block);
        if (!list->empty() && !world::positionLess(list->back(), e))
            throw Damaged("its edits are not in order, or one is given twice");
        list->push_back(e);
    }
    image.edits = std::move(list);
    if (in.left != 0) throw Damaged(std::to_string(in.left) + " bytes more than its state");
    for (std::size_t i = 0; i < keys.size(); ++i) balls.images[keys[i]] = image.hairBalls[i].image;
    return image;
}

std::uint64_t checksum(std::string_view bytes) {
    core::Hasher h;
    h.bytes(bytes.data(), bytes.size());
    return h.value();
}

} // namespace

std::filesystem::path keyframeFilePath(const std::filesystem::path& recording) {
    std::error_code ec;
    std::filesystem::path real = std::filesystem::canonical(recording, ec);
    if (ec) real = std::filesystem::weakly_canonical(recording, ec);
    if (ec) real = recording;
    real += ".keys";
    return real;
}

KeyframeFileWriter::KeyframeFileWriter(std::uint64_t startTick, std::uint64_t interval)
    : m_startTick(startTick), m_interval(interval) {
    if (interval == 0) throw std::invalid_argument("the keyframe file's interval must be at least 1 tick");
}

void KeyframeFileWriter::add(const game::GameState& state, std::uint64_t stateHash) {
    auto image = std::make_unique<game::StateImage>(game::takeImage(state, m_previous.get()));
    std::string payload;
    encodeImage(
        *image,
        [&](std::uint64_t serial, std::uint64_t generation) {
            if (!m_previous) return false;
            for (const game::StateImage::Ball& b : m_previous->hairBalls)
                if (b.serial == serial && b.generation == generation) return true;
            return false;
        },
        payload);
    Out o{m_bytes};
    o.put(image->tick), o.put(stateHash), o.put(static_cast<std::uint64_t>(payload.size())), o.put(checksum(payload));
    m_bytes += payload;
    ++m_count;
    m_previous = std::move(image);
}

void KeyframeFileWriter::write(const std::filesystem::path& path) const {
    if (m_count == 0) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(path, ec)) std::filesystem::remove(path, ec);
        return;
    }
    core::AtomicFile out(path);
    std::string head(kKeyframeFileMagic);
    Out o{head};
    o.put(m_startTick), o.put(m_interval);
    out.stream().write(head.data(), static_cast<std::streamsize>(head.size()));
    out.stream().write(m_bytes.data(), static_cast<std::streamsize>(m_bytes.size()));
    out.commit();
}

KeyframeFileLoad readKeyframeFile(const std::filesystem::path& path, const Recording& recording,
                                  const game::GameDef& def) {
    KeyframeFileLoad load;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return load;
    const std::string name = path.string();
    const auto warn = [&](const std::string& what) { load.warnings.push_back(name + ": " + what); };
    std::ifstream file(path, std::ios::binary);
    std::string bytes;
    if (file) bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    if (!file && !file.eof()) {
        warn("cannot be read; seeks replay from the start world");
        return load;
    }
    In in{bytes.data(), bytes.size()};
    std::uint64_t startTick = 0;
    try {
        if (bytes.compare(0, kKeyframeFileMagic.size(), kKeyframeFileMagic) != 0) throw Damaged("no MCKEYS2 tag");
        in.p += kKeyframeFileMagic.size(), in.left -= kKeyframeFileMagic.size();
        startTick = in.get<std::uint64_t>("its start tick");
        load.interval = in.get<std::uint64_t>("its interval");
    } catch (const Damaged& e) {
        warn(std::string("not a keyframe file (") + e.what() + "); seeks replay from the start world");
        return load;
    }
    if (startTick != recording.header.startTick) {
        warn("its keyframes are of a recording that starts at tick " + std::to_string(startTick) + ", this one at " +
             std::to_string(recording.header.startTick) + " (a stale file); seeks replay from the start world");
        return load;
    }
    BallMap balls;
    std::uint64_t before = startTick;
    while (in.left > 0) {
        const std::size_t offset = bytes.size() - in.left;
        std::uint64_t tick = 0, hash = 0, length = 0, sum = 0;
        try {
            tick = in.get<std::uint64_t>("a keyframe's tick"), hash = in.get<std::uint64_t>("its hash");
            length = in.get<std::uint64_t>("its length"), sum = in.get<std::uint64_t>("its checksum");
            if (length > in.left) throw Damaged("its length runs past the end of the file");
            if (tick <= before || tick > recording.endTick) throw Damaged("its tick is out of order");
        } catch (const Damaged& e) {
            warn("cut short or damaged at byte " + std::to_string(offset) + " (" + e.what() +
                 "): the keyframes from there on are left out");
            break;
        }
        const std::string_view payload(in.p, length);
        in.p += length, in.left -= length;
        before = tick;
        const std::string which = "the keyframe at tick " + std::to_string(tick);
        const auto recorded = recording.hashes.find(tick);
        if (recorded == recording.hashes.end() || recorded->second != hash) {
            warn(which + " is not of this recording (its state hash is not the one recorded at that tick): left out");
            continue;
        }
        if (checksum(payload) != sum) {
            warn(which + " is damaged (its checksum does not match): left out; a seek past it goes from an earlier "
                         "keyframe");
            continue;
        }
        try {
            game::StateImage image = decodeImage(payload, def, balls);
            if (image.tick != tick) throw Damaged("it holds the state of tick " + std::to_string(image.tick));
            load.frames.emplace(tick, FileKeyframe{std::move(image), hash});
        } catch (const std::exception& e) { // Damaged, or what a value the checks let through made a constructor throw
            warn(which + " cannot be read (" + e.what() + "): left out");
        }
    }
    return load;
}

} // namespace session
