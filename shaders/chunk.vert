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

void main() {
    vec3 p = vec3(aPosFace.xyz) + uOffset;
    gl_Position = uViewProj * vec4(p, 1.0);
    vec3 n = kNormals[aPosFace.w];
    // Sky light from above plus a directional sun; occlusion darkens corners.
    float sky = 0.55 + 0.25 * n.y;
    float sun = 0.35 * max(dot(n, uSunDir), 0.0);
    float ao = 0.45 + 0.55 * float(aUvTileAo.w) / 3.0;
    vLight = (sky + sun) * ao;
    vUvLayer = vec3(vec2(aUvTileAo.xy), float(aUvTileAo.z));
    vDistance = length(p);
}
