#version 330 core
// The sky of the time of day (render/daylight.h): a gradient from the fog colour at the horizon to the
// zenith's, the sun's disc and glow, the moon's disc, and stars that fade in as the sun sinks.
in vec3 vRay;
uniform vec3 uFogColor;
uniform vec3 uZenithColor;
uniform vec3 uSunDir;
uniform vec3 uMoonDir;
uniform vec3 uDiscs; // the sun's disc, the moon's disc, the stars: how bright each is drawn, 0..1
out vec4 fragColor;

// A fixed random number for each cell of a grid on the sky (stars stay where they are as the view turns).
float cellRandom(vec3 cell) { return fract(sin(dot(cell, vec3(12.9898, 78.233, 45.164))) * 43758.5453); }

void main() {
    vec3 dir = normalize(vRay);
    float up = clamp(dir.y, 0.0, 1.0);
    vec3 sky = mix(uFogColor, uZenithColor, sqrt(up));
    float sun = pow(max(dot(dir, uSunDir), 0.0), 600.0) * uDiscs.x;
    float moon = smoothstep(0.99955, 0.99975, dot(dir, uMoonDir)) * uDiscs.y;
    float star = 0.0;
    if (uDiscs.z > 0.0 && dir.y > 0.0) {
        float r = cellRandom(floor(dir * 220.0));
        star = step(0.9975, r) * (0.4 + 0.6 * fract(r * 977.0)) * uDiscs.z * smoothstep(0.0, 0.15, dir.y);
    }
    fragColor = vec4(sky + vec3(1.0, 0.95, 0.8) * sun + vec3(0.85, 0.88, 0.95) * moon + vec3(star), 1.0);
}
