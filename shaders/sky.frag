#version 330 core
in vec3 vRay;
uniform vec3 uFogColor;
uniform vec3 uZenithColor;
uniform vec3 uSunDir;
out vec4 fragColor;
void main() {
    vec3 dir = normalize(vRay);
    float up = clamp(dir.y, 0.0, 1.0);
    vec3 sky = mix(uFogColor, uZenithColor, sqrt(up));
    float sun = pow(max(dot(dir, uSunDir), 0.0), 600.0);
    fragColor = vec4(sky + vec3(1.0, 0.95, 0.8) * sun, 1.0);
}
