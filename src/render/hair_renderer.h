// Hair strands as line strips: every active strand of every ball in view in one streamed vertex buffer
// and one draw call (strips separated by primitive restart), positions interpolated between the last
// two ticks, coloured from a darker root to a lighter tip of the ball's colour. The strands of a ball
// whose nodes' box lies wholly outside the view frustum are left out: every segment lies in that box,
// and a line one pixel wide draws nothing outside the view.
#pragma once
#include <cstdint>
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "game/hair_ball.h"
#include "render/frustum.h"
#include "render/gl.h"
#include "render/line_renderer.h"
#include "render/shader.h"

namespace render {

class HairRenderer {
public:
    explicit HairRenderer(const std::filesystem::path& dataDir);
    ~HairRenderer();
    HairRenderer(const HairRenderer&) = delete;
    HairRenderer& operator=(const HairRenderer&) = delete;

    // Positions relative to `eye`; `frustum` in the same coordinates, or null to keep every ball. `light`: the
    // light where the ball is, by colour (localTint), which its colours are multiplied by. False when left out
    // (not in view).
    bool add(const game::HairBall& ball, float alpha, const glm::vec3& eye, const Frustum* frustum,
             const glm::vec3& light = glm::vec3(1.0f));
    // tint: the light the lines are seen in, by colour (1: their own colours).
    void flush(const glm::mat4& viewProjection, const glm::vec3& tint = glm::vec3(1.0f));
    std::size_t lastVertexCount() const { return m_lastVertices; }

private:
    using Vertex = ColouredVertex;
    ShaderProgram m_shader;
    GLint m_uViewProj, m_uTint;
    GLuint m_vao = 0, m_vbo = 0, m_ibo = 0;
    std::vector<Vertex> m_vertices;
    std::vector<std::uint32_t> m_indices;
    std::size_t m_lastVertices = 0;
};

} // namespace render
