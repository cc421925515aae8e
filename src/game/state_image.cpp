#include "game/state_image.h"

#include <optional>
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
    // it was. A ball of the image's serial and generation is in the image's state already (a sleeping one, most
    // often): it is kept rather than made again. A ball made from the image takes its serial and generation, which
    // stand for that state along the timeline the keyframes were taken on.
    const std::size_t n = image.hairBalls.size();
    std::vector<std::size_t> kept(n, state.hairBalls.size());
    std::vector<std::optional<HairBall>> made(n);
    for (std::size_t i = 0; i < n; ++i) {
        const StateImage::Ball& b = image.hairBalls[i];
        for (std::size_t j = 0; j < state.hairBalls.size(); ++j) {
            if (state.hairBalls[j].serial() == b.serial && state.hairBalls[j].generation() == b.generation) kept[i] = j;
        }
        if (kept[i] == state.hairBalls.size()) made[i].emplace(*b.image, b.serial, b.generation);
    }
    std::vector<HairBall> balls;
    balls.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
        balls.push_back(made[i] ? std::move(*made[i]) : std::move(state.hairBalls[kept[i]]));
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
