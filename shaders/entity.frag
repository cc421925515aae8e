#version 330 core
in vec3 vColor;
in float vDistance;
uniform vec3 uFogColor;
uniform vec2 uFogRange;
out vec4 fragColor;
void main() {
    float fog = clamp((vDistance - uFogRange.x) / (uFogRange.y - uFogRange.x), 0.0, 1.0);
    fragColor = vec4(mix(vColor, uFogColor, fog * fog), 1.0);
}
