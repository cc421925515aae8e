#version 330 core
// A full-screen triangle at the far plane. The view ray is computed per vertex: it is linear in screen
// space, so interpolating it is exact and the fragment shader only normalises it.
uniform mat4 uInvViewProj;
out vec3 vRay;
void main() {
    vec2 p = vec2((gl_VertexID == 1) ? 3.0 : -1.0, (gl_VertexID == 2) ? 3.0 : -1.0);
    vec4 far = uInvViewProj * vec4(p, 1.0, 1.0);
    vec4 near = uInvViewProj * vec4(p, -1.0, 1.0);
    vRay = far.xyz / far.w - near.xyz / near.w;
    gl_Position = vec4(p, 1.0, 1.0);
}
