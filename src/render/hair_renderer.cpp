#include "render/hair_renderer.h"

#include "render/line_renderer.h"

#include <cstddef>
#include <limits>

#include <glm/common.hpp>

namespace render {

namespace {
constexpr std::uint32_t kRestart = 0xFFFFFFFFu;
}

HairRenderer::HairRenderer(const std::filesystem::path& dataDir)
    : m_shader(dataDir / "shaders" / "line.vert", dataDir / "shaders" / "line.frag") {
    m_uViewProj = m_shader.uniform("uViewProj");
    m_uTint = m_shader.uniform("uTint");
    glGenVertexArrays(1, &m_vao);
    glGenBuffers(1, &m_vbo);
    glGenBuffers(1, &m_ibo);
    glBindVertexArray(m_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_ibo);
    describeColouredVertices();
    glBindVertexArray(0);
}

HairRenderer::~HairRenderer() {
    glDeleteVertexArrays(1, &m_vao);
    glDeleteBuffers(1, &m_vbo);
    glDeleteBuffers(1, &m_ibo);
}

bool HairRenderer::add(const game::HairBall& ball, float alpha, const glm::vec3& eye, const Frustum* frustum,
                       const glm::vec3& light) {
    const physics::HairSolver& h = ball.solver();
    const int strands = h.strands(), nodes = h.nodesPerStrand(), active = h.activeStrands();
    const float *x = h.x(), *y = h.y(), *z = h.z(), *px = h.prevX(), *py = h.prevY(), *pz = h.prevZ();
    const auto at = [&](int s, int n) {
        const std::size_t i =
            static_cast<std::size_t>(n) * static_cast<std::size_t>(strands) + static_cast<std::size_t>(s);
        const glm::vec3 prev(px[i], py[i], pz[i]), cur(x[i], y[i], z[i]);
        return prev + (cur - prev) * alpha - eye;
    };
    // The box of the nodes as drawn: a ball whose hair is wholly outside the view costs the vertex stage
    // nothing. Nodes of a strand are stored apart (node-major), so this pass reads them in order.
    glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
    for (int n = 0; n < nodes; ++n) {
        for (int s = 0; s < active; ++s) {
            const glm::vec3 p = at(s, n);
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
    }
    if (active == 0 || (frustum != nullptr && !frustum->intersectsBox(low, high))) return false;
    const glm::vec3 colour = ball.def().colour * light;
    for (int s = 0; s < active; ++s) {
        const auto first = static_cast<std::uint32_t>(m_vertices.size());
        for (int n = 0; n < nodes; ++n) {
            const float t = nodes > 1 ? static_cast<float>(n) / static_cast<float>(nodes - 1) : 1.0f;
            m_vertices.push_back({at(s, n), glm::vec4(colour * (0.45f + 0.65f * t), 1.0f)});
            m_indices.push_back(first + static_cast<std::uint32_t>(n));
        }
        m_indices.push_back(kRestart);
    }
    return true;
}

void HairRenderer::flush(const glm::mat4& viewProjection, const glm::vec3& tint) {
    m_lastVertices = m_vertices.size();
    if (m_vertices.empty()) return;
    m_shader.use();
    glUniformMatrix4fv(m_uViewProj, 1, GL_FALSE, &viewProjection[0][0]);
    glUniform3fv(m_uTint, 1, &tint[0]);
    glBindVertexArray(m_vao);
    // Orphan and refill: the driver hands out fresh storage instead of waiting for last frame's draw.
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(Vertex)), nullptr, GL_STREAM_DRAW);
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(Vertex)), m_vertices.data());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_indices.size() * sizeof(std::uint32_t)), nullptr,
                 GL_STREAM_DRAW);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(m_indices.size() * sizeof(std::uint32_t)),
                    m_indices.data());
    glEnable(GL_PRIMITIVE_RESTART);
    glPrimitiveRestartIndex(kRestart);
    glDrawElements(GL_LINE_STRIP, static_cast<GLsizei>(m_indices.size()), GL_UNSIGNED_INT, nullptr);
    glDisable(GL_PRIMITIVE_RESTART);
    glBindVertexArray(0);
    m_vertices.clear();
    m_indices.clear();
}

} // namespace render
