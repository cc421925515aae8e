#version 330 core
// Chunk vertices are 8 bytes: corner (chunk-local 0..32, the low six bits of x, y, z) and face; texture
// coordinates in blocks (the low six bits of u, v), atlas layer and ambient occlusion (0..3); the corner's smooth
// sunlight and block light's red (0..15) in the high halves of the face and occlusion bytes, its green in the
// top two bits of x and y, its blue in those of z and u (world::ChunkVertex). Positions are drawn relative to
// the camera so that float precision holds far from the origin.
layout(location = 0) in uvec4 aPosFace;
layout(location = 1) in uvec4 aUvTileAo;

uniform mat4 uViewProj;   // view (rotation only) * projection
uniform vec3 uOffset;     // chunk origin minus camera position
uniform vec3 uSunDir;     // towards the sun (the moon at night), normalised
uniform vec3 uSunColour;  // its light by colour: 1 at noon (render/daylight.h)
uniform vec3 uSkyColour;  // the sky's light by colour: 1 at noon
uniform vec3 uLampColour; // the lamps' light by colour (render::kLampColour)
uniform uint uEmissiveTiles; // bit t: tile t belongs to a block that gives light (the lamp), drawn unshaded
uniform vec2 uHalfViewport; // pixels per unit of normalised device coordinates, along x and y

out vec3 vUvLayer;
out vec3 vLight;
out float vDistance;

const vec3 kNormals[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
// Greedy quads meet the corners of smaller quads partway along their edges (T-junctions), where the
// rasteriser's rounding can leave a gap a fraction of a pixel wide that shows what lies behind (the sky,
// or a far chunk). Each corner moves outward within its face, along each of the face's two axes, by as
// much as moves it kSealPixels on the screen there, and its texture coordinates with it (the texture
// stays where it was on the face): neighbouring quads overlap by about twice that anywhere along their
// edges (a screen position along an edge is interpolated between its corners'), and no gap is left.
const float kSealPixels = 0.02;
// A light level's brightness: each level below full is 0.82 of the one above (level 0 is 5 % of level 15).
float levelBrightness(float level) { return pow(0.82, 15.0 - level); }

void main() {
    uvec3 corner = aPosFace.xyz & 63u;
    uvec2 uv = aUvTileAo.xy & 63u;
    vec3 p = vec3(corner) + uOffset;
    uint face = aPosFace.w & 7u;
    uint axis = face >> 1u; // of the normal: 0 x, 1 y, 2 z
    // The axes a face's rows (v) and columns (u) run along, and whether they count down along them
    // (world::kDirs in src/world/mesh_quads.h): u and v are 0 at one end of a quad and its size at the other.
    int vAxis = axis == 1u ? 2 : 1;
    int uAxis = axis == 0u ? 2 : 0;
    bool vFlip = axis != 1u, uFlip = face == 0u || face == 5u;
    vec2 uvOut = vec2(uv.x > 0u ? 1.0 : -1.0, uv.y > 0u ? 1.0 : -1.0); // outward in u, v
    vec4 clip = uViewProj * vec4(p, 1.0);
    vec2 seal = vec2(0.0); // blocks along u and v
    if (clip.w > 1.0e-3) {
        // Pixels the screen position moves per block along a world axis here: d(xy / w) is
        // (column.xy w - xy column.w) / w^2. At most a thousandth of the distance, for a face seen
        // edge-on.
        vec2 du = (uViewProj[uAxis].xy * clip.w - clip.xy * uViewProj[uAxis].w) * uHalfViewport;
        vec2 dv = (uViewProj[vAxis].xy * clip.w - clip.xy * uViewProj[vAxis].w) * uHalfViewport;
        float most = 1.0e-3 * clip.w;
        seal = min(kSealPixels * clip.w * clip.w / max(vec2(length(du), length(dv)), vec2(1.0e-30)), vec2(most));
        vec3 along = vec3(0.0);
        along[uAxis] = uFlip ? -uvOut.x : uvOut.x;
        along[vAxis] = vFlip ? -uvOut.y : uvOut.y;
        along[uAxis] *= seal.x;
        along[vAxis] *= seal.y;
        p += along;
        clip = uViewProj * vec4(p, 1.0);
    }
    gl_Position = clip;
    vec3 n = kNormals[face];
    // Sky light from above plus a directional sun, each coloured by the time of day and scaled by the
    // corner's sunlight: the direct sun by its square, so that it fades faster than the sky's light under an
    // overhang. The lamps' block light is the same day and night, each colour channel its own level; where both
    // reach, the brighter wins, channel by channel. Occlusion darkens corners.
    float sunLevel = levelBrightness(float(15u - (aPosFace.w >> 4u)));
    uvec3 colour = uvec3(aUvTileAo.w >> 4u, (aPosFace.x >> 6u) | ((aPosFace.y >> 6u) << 2u),
                         (aPosFace.z >> 6u) | ((aUvTileAo.x >> 6u) << 2u));
    vec3 blockLevel = vec3(levelBrightness(float(colour.r)), levelBrightness(float(colour.g)),
                           levelBrightness(float(colour.b))) * vec3(notEqual(colour, uvec3(0u)));
    float sky = (0.55 + 0.25 * n.y) * sunLevel;
    float sun = 0.35 * max(dot(n, uSunDir), 0.0) * sunLevel * sunLevel;
    float ao = 0.45 + 0.55 * float(aUvTileAo.w & 3u) / 3.0;
    vLight = max(sky * uSkyColour + sun * uSunColour, (0.75 + 0.2 * n.y) * blockLevel * uLampColour) * ao;
    uint tile = aUvTileAo.z;
    if (tile < 32u && ((uEmissiveTiles >> tile) & 1u) != 0u) vLight = vec3(1.0); // it glows
    vUvLayer = vec3(vec2(uv) + seal * uvOut, float(aUvTileAo.z));
    vDistance = length(p);
}
