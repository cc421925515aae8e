// Lit, coloured solids for the objects that live in the world but are not blocks: boxes and spheres,
// batched into one dynamic buffer and drawn in one call per frame. Positions are camera-relative.
// Every shape is closed and its triangles are counter-clockwise seen from outside, so the scene draws
// them with back faces culled.
#pragma once
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "game/object_shapes.h"
#include "render/chunk_renderer.h"
#include "render/gl.h"
#include "render/shader.h"

namespace render {

class EntityRenderer {
public:
    explicit EntityRenderer(const std::filesystem::path& dataDir);
    ~EntityRenderer();
    EntityRenderer(const EntityRenderer&) = delete;
    EntityRenderer& operator=(const EntityRenderer&) = delete;

    struct Vertex {
        glm::vec3 position, normal, color;
        // The brightness of the sunlight where the shape stands (levelBrightness) and the lamps' light there by
        // colour (lampLight): set by addTriangle from setLocalLight.
        glm::vec4 light{1.0f, 0.0f, 0.0f, 0.0f};
    };
    // The light levels where the next shapes stand, until set again (the open sky to begin with): sunlight
    // and the block light's red, green and blue.
    void setLocalLight(int sun, glm::ivec3 colour);
    void addBox(const glm::vec3& min, const glm::vec3& max, const glm::vec3& color);
    void addSphere(const glm::vec3& centre, float radius, const glm::vec3& color);
    // One of the shapes objects are drawn and hit as (game/object_shapes.h), moved by -origin (the camera).
    void addShape(const game::Shape& shape, const glm::vec3& origin);
    // The triangles added since the last flush, three vertices each (for tests).
    const std::vector<Vertex>& batched() const { return m_vertices; }
    void flush(const glm::mat4& viewProjection, const ChunkLighting& light);

private:
    void addTriangle(const Vertex& a, const Vertex& b, const Vertex& c);
    // A box given by its eight corners (in the order of addBox's) and its three face normals x, y, z.
    void addCorners(const glm::vec3 (&c)[8], const glm::vec3 (&normals)[3], const glm::vec3& color);

    ShaderProgram m_shader;
    GLint m_uViewProj, m_uSunDir, m_uSunColour, m_uSkyColour, m_uLampColour, m_uFogColor, m_uFogRange;
    GLuint m_vao = 0, m_vbo = 0;
    std::vector<Vertex> m_vertices;
    std::vector<glm::vec3> m_unitSphere; // triangle list of a unit sphere, built once
    glm::vec4 m_light{1.0f, 0.0f, 0.0f, 0.0f};
};

} // namespace render
