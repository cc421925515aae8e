#version 330 core
in vec3 vUvLayer;
in vec3 vLight;
in float vDistance;

uniform sampler2DArray uAtlas;
uniform vec3 uFogColor;
uniform vec2 uFogRange;   // start, end (blocks)

out vec4 fragColor;

void main() {
    vec3 albedo = texture(uAtlas, vUvLayer).rgb;
    float fog = clamp((vDistance - uFogRange.x) / (uFogRange.y - uFogRange.x), 0.0, 1.0);
    fragColor = vec4(mix(albedo * vLight, uFogColor, fog * fog), 1.0);
}
