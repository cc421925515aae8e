// The checks that refuse a bad record, with their messages: for each table, what a value read from a file must
// be for the game to trust it (ranges, the world border, the physics' own validation, a place the game would
// have put it), and the repairs made instead of a refusal (a player lifted out of blocks, a runaway slot
// marked diverged). world_load.cpp reads each record and calls these; a BadValue skips the record there.
#include "save/store_internal.h"

#include <cstdio>
#include <glm/geometric.hpp>

#include "core/quote.h"
#include "game/hair_ball.h"
#include "game/player.h"
#include "game/space.h"
#include "world/chunk.h"

namespace save {

// Table meta: the world's own values (a bad one refuses the file, readMeta says so).
void RecordReader::checkMeta(const game::StateMeta& meta) {
    if (static_cast<std::int64_t>(meta.tick) < 0) throw BadValue("meta tick is negative");
    if (const std::string day = game::checkDayClock(meta.day); !day.empty()) throw BadValue("meta " + day);
}

// Table player (a bad player is reset to the spawn point, readPlayer says so).
void RecordReader::checkPlayer(const game::Player& p) {
    if (!game::insideBorder(p.position)) throw BadValue("position is outside the world border");
    // The game's fastest motion is a 60 m/s fall; a saved velocity far beyond it is not the game's.
    constexpr float kFastest = 1000.0f;
    if (!(glm::length(p.velocity) <= kFastest)) throw BadValue("velocity is above 1000 m/s");
    if (!(p.yaw >= 0.0f && p.yaw < 360.0f)) throw BadValue("yaw is outside [0, 360)");
    if (std::abs(p.pitch) > 89.0f) throw BadValue("pitch is outside -89..89");
    if (p.selectedSlot < 0 || p.selectedSlot >= game::kHotbarSize)
        throw BadValue("selected_slot = " + std::to_string(p.selectedSlot) + " is outside 0.." +
                       std::to_string(game::kHotbarSize - 1));
}

// Inside blocks (a world edited by hand): lifted out as after a teleport, and said.
void RecordReader::placePlayer(game::Player& p) {
    const float savedY = p.position.y;
    if (game::liftOutOfBlocks(p, *m_world)) {
        m_warnings.push_back(fileName(m_file) +
                             ": table player, row 0: inside blocks at y = " + core::numberForMessage(savedY) +
                             ": lifted to y = " + core::numberForMessage(p.position.y));
    }
}

// One edit of a chunk_edits blob: why it is skipped, or empty when it is good.
std::string RecordReader::editProblem(unsigned index, unsigned block, std::set<unsigned>& seen) const {
    std::string why;
    if (index >= static_cast<unsigned>(world::kChunkVolume))
        why = "position index " + std::to_string(index) + " is outside the chunk";
    else if (block >= static_cast<unsigned>(blockIdsOfSchema(m_version)))
        why = "block id " + std::to_string(block) + " is out of range" +
              (block < static_cast<unsigned>(world::kBlockTypeCount)
                   ? " for schema " + std::to_string(m_version) + " (" +
                         std::string(world::blockInfo(static_cast<world::BlockType>(block)).name) +
                         " came in a later one)"
                   : "");
    else if (!seen.insert(index).second)
        why = "position index " + std::to_string(index) + " is edited twice";
    return why;
}

// Table pendulum_sets, with its four slots read into rec.
void RecordReader::checkPendulumSet(PendulumSetRecord& rec, const std::string& row) {
    constexpr auto kFar = static_cast<std::int64_t>(game::kWorldBorder); // blocks
    if (rec.base.x < -kFar || rec.base.x >= kFar || rec.base.z < -kFar || rec.base.z >= kFar || rec.base.y < 0 ||
        rec.base.y >= world::kWorldHeight)
        throw BadValue("position (" + std::to_string(rec.base.x) + ", " + std::to_string(rec.base.y) + ", " +
                       std::to_string(rec.base.z) + ") is outside the world");
    // Build it once: the physics' own validation is the last word on what is consistent. Any
    // exception from values in the file (Boost.Math reports its own errors too) makes the
    // record bad; it is skipped with the reason, never allowed to end the game.
    std::array<world::Aabb, 5> boxes{};
    try {
        game::PendulumSet probe(rec.base, rec.def);
        probe.restore(rec.internals);
        boxes = game::pendulumSetBoxes(probe);
    } catch (const std::exception& e) {
        throw BadValue(e.what());
    }
    // Where the game would have put it (game::placementProblem): on a block, not over air; its post and swings
    // clear of blocks and of the sets before it.
    const glm::ivec3 below = rec.base - glm::ivec3(0, 1, 0);
    if (!world::isSolid(m_world->get(below)))
        throw BadValue("it stands over air: the block under it, (" + std::to_string(below.x) + ", " +
                       std::to_string(below.y) + ", " + std::to_string(below.z) +
                       "), is not solid (the game places a set on a block)");
    for (const world::Aabb& box : boxes) {
        if (world::intersectsSolid(*m_world, box))
            throw BadValue("its post or a swing is inside blocks (the game places a set where it has room)");
        for (std::size_t j = 0; j < m_setBoxes.size(); ++j) {
            for (const world::Aabb& other : m_setBoxes[j])
                if (game::boxesOverlap(box, other))
                    throw BadValue("it overlaps the set of row " + m_setRows[j] + " (the game places sets apart)");
        }
    }
    m_setBoxes.push_back(boxes);
    m_setRows.push_back(row);
    // A slot beyond what the game steps (its own divergence test, or past the physics' bounds on
    // a state) that is not marked diverged would stand frozen: marked, and said.
    for (std::size_t k = 0; k < game::kPendulumSlots; ++k) {
        const physics::PendulumState st = rec.internals.slots[k].state;
        if (rec.internals.diverged[k] || (std::abs(st.theta) <= physics::kMaxInitialAngle && std::abs(st.omega) <= 1e6))
            continue;
        rec.internals.diverged[k] = true;
        m_warnings.push_back(fileName(m_file) + ": table pendulum_slots, set " + row + " slot " + std::to_string(k) +
                             ": theta " + core::numberForMessage(st.theta) + ", omega " +
                             core::numberForMessage(st.omega) + " is beyond what the game steps: marked diverged");
    }
}

// A hair ball's solver: one this build does not know refuses the whole load (RefusedRecord), never a skip.
void RecordReader::checkSolver(const std::string& name, const std::string& row) const {
    if (!physics::hairMethodFromName(name)) {
        throw RefusedRecord(fileName(m_file) + ": table hair_balls, row " + row + ": solver " +
                            core::quoteForMessage(name) + " is unknown to this build (it knows " +
                            physics::hairMethodNames() +
                            "); the world may come from a newer Minecrappy. Not opened, not changed");
    }
}

// Table hair_balls: a ball the game could simulate. Its size is checked before its hair blob is decoded.
void RecordReader::checkHairBall(const HairBallRecord& rec) {
    if (!game::insideBorder(rec.centre)) throw BadValue("centre is outside the world border");
    const physics::HairParams& h = rec.def.hair;
    if (h.strands < 1 || h.nodesPerStrand < 2 ||
        static_cast<std::int64_t>(h.strands) * h.nodesPerStrand > kMaxSavedHairNodes) {
        throw BadValue("strands x nodes_per_strand = " + std::to_string(h.strands) + " x " +
                       std::to_string(h.nodesPerStrand) + " is outside 1 x 2 .. " + std::to_string(kMaxSavedHairNodes) +
                       " nodes");
    }
    try {
        game::validateHairBallDef(rec.def); // the game's limits, physics::validateHairParams included
    } catch (const std::invalid_argument& e) {
        throw BadValue(e.what());
    }
}

void RecordReader::checkHairBallPlace(const HairBallRecord& rec, const Snapshot& s) const {
    // Where the game would have put it: in free space (no block) and apart from the balls before it.
    if (game::sphereOverlapsSolid(*m_world, rec.centre, rec.def.radius))
        throw BadValue("it is inside blocks (the game places balls in free space)");
    for (std::size_t j = 0; j < s.hairBalls.size(); ++j) {
        const HairBallRecord& other = s.hairBalls[j];
        if (glm::distance(other.centre, rec.centre) < other.def.radius + rec.def.radius)
            throw BadValue("it overlaps the ball of row " + m_ballRows[j] + " (the game places balls apart)");
    }
    for (std::size_t j = 0; j < m_setBoxes.size(); ++j) {
        for (const world::Aabb& box : m_setBoxes[j])
            if (game::sphereOverlapsBox(rec.centre, rec.def.radius, box))
                throw BadValue("it overlaps the pendulum set of row " + m_setRows[j] +
                               " (the game keeps balls out of a set's post and swings)");
    }
}

} // namespace save
