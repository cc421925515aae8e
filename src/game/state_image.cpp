#include "game/state_image.h"

#include <stdexcept>

namespace game {

StateImage takeImage(const GameState& state, const StateImage* previous) {
    StateImage image;
    image.def = state.def;
    image.tick = state.tick;
    image.worldIdentity = state.world.identity();
    image.worldRevision = state.world.revision();
    if (previous && previous->edits && previous->worldIdentity == image.worldIdentity &&
        previous->worldRevision == image.worldRevision) {
        image.edits = previous->edits;
    } else {
        image.edits = std::make_shared<const std::vector<world::BlockEdit>>(state.world.edits());
    }
    image.player = state.player;
    image.previousPlayer = state.previousPlayer;
    image.paused = state.paused;
    image.day = state.day;
    image.pendulumSets = state.pendulumSets;
    image.hairBalls.reserve(state.hairBalls.size());
    for (std::size_t i = 0; i < state.hairBalls.size(); ++i) {
        const HairBall& ball = state.hairBalls[i];
        StateImage::Ball b{nullptr, ball.serial(), ball.generation()};
        if (previous) {
            for (const StateImage::Ball& p : previous->hairBalls) {
                if (p.serial == b.serial && p.generation == b.generation) b.image = p.image;
            }
        }
        if (!b.image) b.image = std::make_shared<const HairBallImage>(ball.image());
        image.hairBalls.push_back(std::move(b));
    }
    image.carriedBall = state.carriedBall;
    image.tickSeconds = state.tickSeconds;
    return image;
}

void restoreImage(GameState& state, const StateImage& image) {
    const world::TerrainDef& t = state.world.terrain();
    if (t.seed != image.def.terrain.seed || t.kind != image.def.terrain.kind)
        throw std::invalid_argument("restoreImage: the image is of another world");
    // The balls first: a ball that cannot be made (it never can, from an image taken of one) leaves the state as
    // it was.
    std::vector<HairBall> balls;
    balls.reserve(image.hairBalls.size());
    for (const StateImage::Ball& b : image.hairBalls) balls.emplace_back(*b.image);
    state.def = image.def;
    state.tick = image.tick;
    state.world.setEdits(*image.edits);
    state.player = image.player;
    state.previousPlayer = image.previousPlayer;
    state.paused = image.paused;
    state.day = image.day;
    state.pendulumSets = image.pendulumSets;
    state.hairBalls = std::move(balls);
    state.carriedBall = image.carriedBall;
    state.tickSeconds = image.tickSeconds;
}

} // namespace game
