// A copy of a game's whole state, taken after a tick and put back in place: what a replay's keyframes hold
// (session/keyframes.h). Unlike a save (save::Snapshot) it leaves nothing out: a carried ball stays carried, the
// hair detail and budget (GameDef), the pendulum sets' traces (the panels' plots), what is drawn between ticks
// (the previous player, each ball's previous centre) and each ball's last step figures come back too, so a
// restored state hashes, dumps, draws and continues exactly as the state it was taken of.
//
// The World is kept: restoring applies the difference in edits (World::setEdits), so only the chunks that
// differ are remeshed. Parts that did not change since the previous image are shared with it rather than
// copied: the edits while the world's revision stands still, and each hair ball while it sleeps (a default
// ball's hair is about 221 KB).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "game/game_state.h"

namespace game {

struct StateImage {
    GameDef def;
    std::uint64_t tick = 0;
    std::shared_ptr<const std::vector<world::BlockEdit>> edits;
    Player player, previousPlayer;
    bool paused = false;
    DayClock day;
    std::vector<PendulumSet> pendulumSets;
    struct Ball {
        std::shared_ptr<const HairBallImage> image;
        std::uint64_t serial = 0, generation = 0; // HairBall's, when the image was taken
    };
    std::vector<Ball> hairBalls;
    std::optional<std::size_t> carriedBall;
    double tickSeconds = 0.0;
    // What tells whether the edits changed: the world they were taken of and its revision then.
    std::uint64_t worldIdentity = 0, worldRevision = 0;
};

// The image of `state`; parts equal to those of `previous` (an image of the same game, taken earlier) are shared
// with it.
StateImage takeImage(const GameState& state, const StateImage* previous = nullptr);
// Puts `image` back into `state`, keeping its World (whose terrain must be the image's: else throws
// std::invalid_argument). Afterwards stateHash(state) is the hash of the state the image was taken of.
void restoreImage(GameState& state, const StateImage& image);

// Bytes an image holds beyond its own struct, each shared part counted by `count` (called with the part's
// address and size; a caller keeping many images counts a part once by its address).
template <class F>
void forEachPart(const StateImage& image, F&& count) {
    if (image.edits) count(image.edits.get(), image.edits->capacity() * sizeof(world::BlockEdit));
    std::size_t sets = 0;
    for (const PendulumSet& s : image.pendulumSets) {
        const PendulumTrace& t = s.trace();
        sets += sizeof(PendulumSet) + (t.time.capacity() + t.exactTheta.capacity() +
                                       kPendulumSlots * (t.theta[0].capacity() + t.energyError[0].capacity())) *
                                          sizeof(float);
    }
    count(&image.pendulumSets, sets);
    for (const StateImage::Ball& b : image.hairBalls) {
        const physics::HairSolverState& h = b.image->hair;
        const std::size_t floats = h.x.capacity() + h.y.capacity() + h.z.capacity() + h.px.capacity() +
                                   h.py.capacity() + h.pz.capacity() + h.cx.capacity() + h.cy.capacity() +
                                   h.cz.capacity() + h.wx.capacity() + h.wy.capacity() + h.wz.capacity();
        count(b.image.get(), sizeof(HairBallImage) + floats * sizeof(float));
    }
}

} // namespace game
