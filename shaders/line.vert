#version 330 core
layout(location = 0) in vec3 aPos;   // relative to the camera
layout(location = 1) in vec4 aColor;
uniform mat4 uViewProj;
uniform vec3 uTint; // the light the lines are seen in (render/daylight.h's sky brightness; 1 at noon)
out vec4 vColor;
void main() {
    vColor = vec4(aColor.rgb * uTint, aColor.a);
    gl_Position = uViewProj * vec4(aPos, 1.0);
}
