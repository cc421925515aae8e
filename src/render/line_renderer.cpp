#include "render/line_renderer.h"

#include <cstddef>

namespace render {

void describeColouredVertices() {
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(ColouredVertex), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(ColouredVertex),
                          reinterpret_cast<const void*>(offsetof(ColouredVertex, color)));
}

LineRenderer::LineRenderer(const std::filesystem::path& dataDir)
    : m_shader(dataDir / "shaders" / "line.vert", dataDir / "shaders" / "line.frag") {
    m_uViewProj = m_shader.uniform("uViewProj");
    m_uTint = m_shader.uniform("uTint");
    glGenVertexArrays(1, &m_vao);
    glGenBuffers(1, &m_vbo);
    glBindVertexArray(m_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    describeColouredVertices();
    glBindVertexArray(0);
}

LineRenderer::~LineRenderer() {
    glDeleteVertexArrays(1, &m_vao);
    glDeleteBuffers(1, &m_vbo);
}

void LineRenderer::addSegment(const glm::vec3& a, const glm::vec3& b, const glm::vec4& color) {
    m_points.push_back({a, color});
    m_points.push_back({b, color});
}

void LineRenderer::addBox(const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& color) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z},
                            {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    for (int i = 0; i < 4; ++i) {
        addSegment(c[i], c[(i + 1) % 4], color);         // bottom ring
        addSegment(c[i + 4], c[(i + 1) % 4 + 4], color); // top ring
        addSegment(c[i], c[i + 4], color);               // uprights
    }
}

void LineRenderer::flush(const glm::mat4& viewProjection, const glm::vec3& tint) {
    if (m_points.empty()) return;
    m_shader.use();
    glUniformMatrix4fv(m_uViewProj, 1, GL_FALSE, &viewProjection[0][0]);
    glUniform3fv(m_uTint, 1, &tint[0]);
    streamAndDraw(m_vao, m_vbo, m_points, GL_LINES);
    m_points.clear();
}

} // namespace render
