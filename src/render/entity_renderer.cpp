#include "render/entity_renderer.h"

#include "render/daylight.h"

#include <cmath>
#include <cstddef>
#include <glm/geometric.hpp>

namespace render {

namespace {
// A unit sphere as a subdivided octahedron: even triangles, no poles to pinch.
std::vector<glm::vec3> buildUnitSphere(int subdivisions) {
    std::vector<glm::vec3> tris = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},  {0, 1, 0},  {-1, 0, 0}, {0, 0, 1},
                                   {-1, 0, 0}, {0, -1, 0}, {0, 0, 1},  {0, -1, 0}, {1, 0, 0},  {0, 0, 1},
                                   {0, 1, 0},  {1, 0, 0},  {0, 0, -1}, {-1, 0, 0}, {0, 1, 0},  {0, 0, -1},
                                   {0, -1, 0}, {-1, 0, 0}, {0, 0, -1}, {1, 0, 0},  {0, -1, 0}, {0, 0, -1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::vector<glm::vec3> next;
        next.reserve(tris.size() * 4);
        for (std::size_t i = 0; i < tris.size(); i += 3) {
            const glm::vec3 a = tris[i], b = tris[i + 1], c = tris[i + 2];
            const glm::vec3 ab = glm::normalize(a + b), bc = glm::normalize(b + c), ca = glm::normalize(c + a);
            for (const glm::vec3& v : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca}) next.push_back(v);
        }
        tris.swap(next);
    }
    return tris;
}
} // namespace

EntityRenderer::EntityRenderer(const std::filesystem::path& dataDir)
    : m_shader(dataDir / "shaders" / "entity.vert", dataDir / "shaders" / "entity.frag"),
      m_unitSphere(buildUnitSphere(2)) {
    m_uViewProj = m_shader.uniform("uViewProj");
    m_uSunDir = m_shader.uniform("uSunDir");
    m_uSunColour = m_shader.uniform("uSunColour");
    m_uSkyColour = m_shader.uniform("uSkyColour");
    m_uLampColour = m_shader.uniform("uLampColour");
    m_uFogColor = m_shader.uniform("uFogColor");
    m_uFogRange = m_shader.uniform("uFogRange");
    glGenVertexArrays(1, &m_vao);
    glGenBuffers(1, &m_vbo);
    glBindVertexArray(m_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    for (GLuint i = 0; i < 3; ++i) {
        glEnableVertexAttribArray(i);
        glVertexAttribPointer(i, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                              reinterpret_cast<const void*>(i * sizeof(glm::vec3)));
    }
    glEnableVertexAttribArray(3);
    glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, light)));
    glBindVertexArray(0);
}

EntityRenderer::~EntityRenderer() {
    glDeleteVertexArrays(1, &m_vao);
    glDeleteBuffers(1, &m_vbo);
}

void EntityRenderer::setLocalLight(int sun, glm::ivec3 colour) {
    const auto channel = [](int level) { return level > 0 ? levelBrightness(level) : 0.0f; };
    m_light = glm::vec4(levelBrightness(sun), channel(colour.r), channel(colour.g), channel(colour.b));
}

void EntityRenderer::addTriangle(const Vertex& a, const Vertex& b, const Vertex& c) {
    for (const Vertex* v : {&a, &b, &c}) {
        m_vertices.push_back(*v);
        m_vertices.back().light = m_light;
    }
}

void EntityRenderer::addCorners(const glm::vec3 (&c)[8], const glm::vec3 (&normals)[3], const glm::vec3& color) {
    // Each face as two counter-clockwise triangles seen from outside.
    struct Face {
        int v[4];
        int axis;
        float sign;
    };
    static constexpr Face kFaces[6] = {{{1, 2, 6, 5}, 0, 1.0f},  {{0, 4, 7, 3}, 0, -1.0f}, {{3, 7, 6, 2}, 1, 1.0f},
                                       {{0, 1, 5, 4}, 1, -1.0f}, {{4, 5, 6, 7}, 2, 1.0f},  {{0, 3, 2, 1}, 2, -1.0f}};
    for (const Face& f : kFaces) {
        const glm::vec3 n = normals[f.axis] * f.sign;
        const Vertex q[4] = {
            {c[f.v[0]], n, color}, {c[f.v[1]], n, color}, {c[f.v[2]], n, color}, {c[f.v[3]], n, color}};
        addTriangle(q[0], q[1], q[2]);
        addTriangle(q[0], q[2], q[3]);
    }
}

void EntityRenderer::addBox(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& color) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    addCorners(c, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, color);
}

void EntityRenderer::addShape(const game::Shape& shape, const glm::vec3& origin) {
    switch (shape.kind) {
    case game::Shape::Kind::Box:
        addBox(shape.a - origin, shape.b - origin, shape.colour);
        return;
    case game::Shape::Kind::Sphere:
        addSphere(shape.a - origin, shape.radius, shape.colour);
        return;
    case game::Shape::Kind::Rod: {
        // The box of the rod's own frame (x along, y = u, z = v): right-handed, so addBox's corner order and
        // winding carry over.
        const game::RodFrame f = game::rodFrame(shape);
        const glm::vec3 a = shape.a - origin;
        const float w = shape.radius;
        const auto at = [&](float x, float y, float z) { return a + f.along * x + f.u * y + f.v * z; };
        const float l = f.length;
        const glm::vec3 c[8] = {at(0, -w, -w), at(l, -w, -w), at(l, w, -w), at(0, w, -w),
                                at(0, -w, w),  at(l, -w, w),  at(l, w, w),  at(0, w, w)};
        addCorners(c, {f.along, f.u, f.v}, shape.colour);
        return;
    }
    }
}

void EntityRenderer::addSphere(const glm::vec3& centre, float radius, const glm::vec3& color) {
    for (std::size_t i = 0; i < m_unitSphere.size(); i += 3) {
        addTriangle({centre + m_unitSphere[i] * radius, m_unitSphere[i], color},
                    {centre + m_unitSphere[i + 1] * radius, m_unitSphere[i + 1], color},
                    {centre + m_unitSphere[i + 2] * radius, m_unitSphere[i + 2], color});
    }
}

void EntityRenderer::flush(const glm::mat4& viewProjection, const ChunkLighting& light) {
    if (m_vertices.empty()) return;
    m_shader.use();
    glUniformMatrix4fv(m_uViewProj, 1, GL_FALSE, &viewProjection[0][0]);
    glUniform3fv(m_uSunDir, 1, &light.sunDirection[0]);
    glUniform3fv(m_uSunColour, 1, &light.sunColour[0]);
    glUniform3fv(m_uSkyColour, 1, &light.skyColour[0]);
    glUniform3fv(m_uLampColour, 1, &kLampColour[0]);
    glUniform3fv(m_uFogColor, 1, &light.fogColor[0]);
    glUniform2f(m_uFogRange, light.fogStart, light.fogEnd);
    streamAndDraw(m_vao, m_vbo, m_vertices, GL_TRIANGLES);
    m_vertices.clear();
}

} // namespace render
