#version 330 core
// Lit, coloured triangles for objects in the world (pendulum sets, hair balls), positioned relative to the
// camera like the chunks, and lit by the light levels where they stand.
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aColor;
layout(location = 3) in vec4 aLight; // brightness of the sunlight, and of the block light's red, green, blue, where it stands
uniform mat4 uViewProj;
uniform vec3 uSunDir;
uniform vec3 uSunColour; // as in chunk.vert
uniform vec3 uSkyColour;
uniform vec3 uLampColour; // the lamps' light by colour (render::kLampColour)
out vec3 vColor;
out float vDistance;
void main() {
    vec3 n = normalize(aNormal);
    // As chunk.vert lights a face: the sky's and the sun's light scaled by the sunlight there (the sun's by its
    // square), or the lamps' where that is brighter.
    vec3 day = ((0.55 + 0.25 * n.y) * uSkyColour + 0.35 * max(dot(n, uSunDir), 0.0) * uSunColour * aLight.x) * aLight.x;
    vec3 light = max(day, (0.75 + 0.2 * n.y) * aLight.yzw * uLampColour);
    vColor = aColor * light;
    vDistance = length(aPos);
    gl_Position = uViewProj * vec4(aPos, 1.0);
}
