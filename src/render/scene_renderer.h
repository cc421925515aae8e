// Draws one frame of the game world: sky, chunks, the outline of the targeted block. The camera is the
// player's eye interpolated between the last two ticks by the loop's alpha. The HUD and panels are
// drawn afterwards by the ui layer. Reads the game state; never changes it.
#pragma once
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>

#include "game/game_state.h"
#include "render/chunk_renderer.h"
#include "render/daylight.h"
#include "render/entity_renderer.h"
#include "render/hair_renderer.h"
#include "render/line_renderer.h"
#include "render/shader.h"
#include "render/texture.h"

namespace render {

struct SceneSettings {
    float fovDegrees = 70.0f;         // vertical field of view
    int viewRadius = 8;               // chunks
    double meshBudgetSeconds = 0.004; // CPU time per frame for streaming chunks; <= 0: all at once
    bool levelOfDetail = true;        // coarser meshes for distant chunks (ChunkRenderer)
    bool occlusionCulling = true;     // draw only chunks the camera can see into (ChunkRenderer::draw)
    // Large screenshots draw the frame in tiles: the whole frame is `frame` pixels (0: the viewport), this draw
    // covers the part from `tileOrigin` (pixels, y down) the size of the viewport; project() answers in
    // `labelSpace` pixels (0: the whole frame), the space Dear ImGui lays the labels out in.
    glm::ivec2 frame{0, 0};
    glm::ivec2 tileOrigin{0, 0};
    glm::ivec2 labelSpace{0, 0};
    float lineWidth = 1.0f; // pixels: hair strands, rods and outlines (a frame drawn K times larger: K)
};

struct Camera {
    glm::vec3 eye{0.0f};
    float yaw = 0.0f, pitch = 0.0f; // degrees
};

struct SceneStats { // what the scene renderer drew and spent on its last frame
    ChunkStats chunks;
    std::size_t hairVertices = 0;
    double cpuMs = 0.0; // CPU time to issue the frame (streaming included)
};

// The eye between the previous and current tick; lookOffset adds mouse motion not yet simulated.
Camera interpolatedCamera(const game::GameState& state, float alpha, glm::vec2 lookOffset = {0.0f, 0.0f});

class SceneRenderer {
public:
    explicit SceneRenderer(const std::filesystem::path& dataDir);
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // alpha: how far between the previous and the current tick to draw moving objects.
    void render(const game::GameState& state, const Camera& camera, glm::ivec2 viewport, const SceneSettings& settings,
                float alpha = 1.0f);
    // Where a world point appears on screen in the last frame (pixels, y down), if in front of the camera.
    std::optional<glm::vec2> project(const glm::vec3& world) const;
    const SceneStats& stats() const { return m_stats; }
    const BlockAtlas& atlas() const { return m_atlas; }
    void holdMeshWorker(bool held) { m_chunks.holdWorker(held); } // tests: ChunkStreaming::holdWorker
    void waitForMeshWorker() { m_chunks.waitForWorker(); }        // tests: ChunkStreaming::waitForWorker

private:
    BlockAtlas m_atlas;
    ChunkRenderer m_chunks;
    LineRenderer m_lines;
    EntityRenderer m_entities;
    std::vector<game::Shape> m_shapes; // one set's shapes, reused frame to frame
    HairRenderer m_hair;
    void drawPendulumSets(const game::GameState& state, const Camera& cam, float alpha);
    glm::mat4 m_lastViewProjection{1.0f};
    glm::vec3 m_lastEye{0.0f};
    glm::ivec2 m_lastViewport{1, 1};
    ShaderProgram m_sky;
    GLint m_skyInvViewProj, m_skyFog, m_skyZenith, m_skySun, m_skyMoon, m_skyDiscs;
    GLuint m_emptyVao = 0;
    SceneStats m_stats;
};

} // namespace render
