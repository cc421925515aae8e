#version 330 core
// Chunk vertices are 8 bytes: corner (chunk-local 0..32) and face; texture coordinates in blocks,
// atlas layer and ambient occlusion (0..3). Positions are drawn relative to the camera so that float
// precision holds far from the origin.
layout(location = 0) in uvec4 aPosFace;
layout(location = 1) in uvec4 aUvTileAo;

uniform mat4 uViewProj;   // view (rotation only) * projection
uniform vec3 uOffset;     // chunk origin minus camera position
uniform vec3 uSunDir;     // towards the sun, normalised

out vec3 vUvLayer;
out float vLight;
out float vDistance;

const vec3 kNormals[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
// Greedy quads meet the corners of smaller quads partway along their edges (T-junctions), where the
// rasteriser's rounding can leave a gap a fraction of a pixel wide that shows what lies behind (the sky,
// or a far chunk). Each corner moves outward within its face by 1e-4 of its distance, about a twentieth
// of a pixel at any distance at 1280x720 (a pixel there spans 1/514 of the distance), and its texture
// coordinates with it: neighbouring quads overlap by that much and no gap is left.
const float kSeal = 1.0e-4;

void main() {
    vec3 p = vec3(aPosFace.xyz) + uOffset;
    uint face = aPosFace.w;
    uint axis = face >> 1u; // of the normal: 0 x, 1 y, 2 z
    // The axes a face's rows (v) and columns (u) run along, and whether they count down along them
    // (world::kDirs in src/world/mesher.cpp): u and v are 0 at one end of a quad and its size at the other.
    vec3 vAxis = axis == 1u ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0);
    vec3 uAxis = axis == 0u ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    bool vFlip = axis != 1u, uFlip = face == 0u || face == 5u;
    vec2 highUV = vec2(aUvTileAo.x > 0u ? 1.0 : -1.0, aUvTileAo.y > 0u ? 1.0 : -1.0);
    float dist = length(p);
    float seal = kSeal * dist;
    p += seal * (vAxis * (vFlip ? -highUV.y : highUV.y) + uAxis * (uFlip ? -highUV.x : highUV.x));
    gl_Position = uViewProj * vec4(p, 1.0);
    vec3 n = kNormals[face];
    // Sky light from above plus a directional sun; occlusion darkens corners.
    float sky = 0.55 + 0.25 * n.y;
    float sun = 0.35 * max(dot(n, uSunDir), 0.0);
    float ao = 0.45 + 0.55 * float(aUvTileAo.w) / 3.0;
    vLight = (sky + sun) * ao;
    // The texture moves with the corner, so it stays where it was on the face: u and v count from 0 at
    // one end of the quad to its size at the other.
    vUvLayer = vec3(vec2(aUvTileAo.xy) + seal * highUV, float(aUvTileAo.z));
    vDistance = dist; // the seal moves it by a ten-thousandth
}
