#version 330 core
// Lit, coloured triangles for objects in the world (pendulum sets, later hair balls), positioned
// relative to the camera like the chunks.
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aColor;
uniform mat4 uViewProj;
uniform vec3 uSunDir;
uniform vec3 uSunColour; // as in chunk.vert
uniform vec3 uSkyColour;
out vec3 vColor;
out float vDistance;
void main() {
    vec3 n = normalize(aNormal);
    vec3 light = (0.55 + 0.25 * n.y) * uSkyColour + 0.35 * max(dot(n, uSunDir), 0.0) * uSunColour;
    vColor = aColor * light;
    vDistance = length(aPos);
    gl_Position = uViewProj * vec4(aPos, 1.0);
}
