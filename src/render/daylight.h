// What the time of day looks like: the sun's and the moon's directions, the light they and the sky give, and
// the colours of the sky and the fog, as pure functions of the hour (game/day_clock.h). No GL here: the
// renderers pass these to their shaders as uniforms, so a whole day passes without remeshing a chunk.
//
// The sun turns once a day about a tilted axis: it rises in the east (+x, a little north) at 6, stands at
// kNoonSun at 12 (the direction the noon goldens are lit from) and sets at 18; the moon is opposite it. Light strengths
// are multipliers of the shaders' own terms: noon is 1 for both the sky's and the sun's.
#pragma once
#include <glm/vec3.hpp>

namespace render {

inline constexpr glm::vec3 kNoonSun{0.35f, 0.85f, 0.4f}; // not normalised; towards the sun at noon

struct Daylight {
    glm::vec3 sunDirection{0.0f}; // towards the sun, normalised (below the horizon at night)
    glm::vec3 moonDirection{0.0f};
    // Towards the light the faces are shaded by: the sun by day, the moon by night.
    glm::vec3 lightDirection{0.0f};
    glm::vec3 lightColour{0.0f}; // that light's strength and colour (noon: 1, 1, 1)
    glm::vec3 skyColour{0.0f};   // the sky's light on every face, by colour (noon: 1, 1, 1; night: dim blue)
    glm::vec3 fogColour{0.0f};   // the horizon and the fog
    glm::vec3 zenithColour{0.0f};
    float stars = 0.0f;                    // how visible the stars are, 0..1
    float sunDisc = 0.0f, moonDisc = 0.0f; // how bright each disc is drawn, 0..1
};

Daylight daylightAt(double hours);

// The sky light's mean strength (its channels' mean), for things lit by the sky alone (hair, rods).
float skyBrightness(const Daylight& d);

// A light level's brightness (0..world::kMaxLight), as shaders/chunk.vert and entity.vert compute it: each level
// below full 0.82 times as bright as the one above it (level 0 is 5 % of full). Block light 0 gives none.
float levelBrightness(int level);
// The lamps' light by colour: a warm white, at its brightest a little under noon's (the shaders' uLampColour).
inline constexpr glm::vec3 kLampColour{1.0f, 0.9f, 0.75f};

// The lamps' light where the block light's levels are `colour` (red, green, blue): each channel's brightness
// (0 at level 0) times kLampColour's.
glm::vec3 lampLight(glm::ivec3 colour);
// What unshaded things (hair, the hotbar's icons) are lit by where the light levels are `sun` and `colour`: the
// sky's light scaled by that sunlight's brightness, or the lamps', whichever is brighter, by colour.
glm::vec3 localTint(const Daylight& d, int sun, glm::ivec3 colour);

} // namespace render
