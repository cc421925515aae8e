#include "render/scene_renderer.h"

#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "world/raycast.h"

namespace render {

namespace {
float lerpAngle(float a, float b, float t) {
    float d = std::fmod(b - a + 540.0f, 360.0f) - 180.0f; // shortest way round
    return a + d * t;
}
} // namespace

Camera interpolatedCamera(const game::GameState& s, float alpha, glm::vec2 lookOffset) {
    const game::Player& a = s.previousPlayer;
    const game::Player& b = s.player;
    Camera c;
    c.eye = glm::mix(game::eyePosition(a, s.def.player), game::eyePosition(b, s.def.player), alpha);
    c.yaw = lerpAngle(a.yaw, b.yaw, alpha) + lookOffset.x;
    c.pitch = glm::clamp(glm::mix(a.pitch, b.pitch, alpha) + lookOffset.y, -89.0f, 89.0f);
    return c;
}

SceneRenderer::SceneRenderer(const std::filesystem::path& dataDir)
    : m_atlas(dataDir / "assets" / "atlas.png"), m_chunks(dataDir), m_lines(dataDir),
      m_sky(dataDir / "shaders" / "sky.vert", dataDir / "shaders" / "sky.frag") {
    m_skyInvViewProj = m_sky.uniform("uInvViewProj");
    m_skyFog = m_sky.uniform("uFogColor");
    m_skyZenith = m_sky.uniform("uZenithColor");
    m_skySun = m_sky.uniform("uSunDir");
    glGenVertexArrays(1, &m_emptyVao);
}

void SceneRenderer::render(const game::GameState& state, const Camera& cam, glm::ivec2 viewport,
                           const SceneSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    m_chunks.update(state.world, cam.eye, settings.viewRadius, settings.meshBudgetSeconds);

    ChunkLighting light;
    light.sunDirection = glm::normalize(light.sunDirection);
    const float viewDistance = static_cast<float>(settings.viewRadius * world::kChunkSize);
    light.fogEnd = viewDistance;
    light.fogStart = viewDistance * 0.55f;

    const float aspect = viewport.y > 0 ? static_cast<float>(viewport.x) / static_cast<float>(viewport.y) : 1.0f;
    const glm::mat4 projection =
        glm::perspective(glm::radians(settings.fovDegrees), aspect, 0.05f, viewDistance + 64.0f);
    const glm::vec3 forward = game::lookDirection(cam.yaw, cam.pitch);
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), forward, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 viewProjection = projection * view;

    glViewport(0, 0, viewport.x, viewport.y);
    glDepthMask(GL_TRUE);
    glClearColor(light.fogColor.r, light.fogColor.g, light.fogColor.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    m_chunks.draw(viewProjection, cam.eye, m_atlas.arrayTexture(), light);

    // Outline of the targeted block (from the simulated eye, as the game uses it for edits).
    if (!state.paused) {
        if (const auto hit = game::targetedBlock(state)) {
            const glm::vec3 lo = glm::vec3(hit->block) - cam.eye - glm::vec3(0.002f);
            m_lines.addBox(lo, lo + glm::vec3(1.004f));
            m_lines.flush(viewProjection, glm::vec4(0.05f, 0.05f, 0.05f, 1.0f));
        }
    }
    glDisable(GL_CULL_FACE);

    // Sky last, at the far plane, where nothing else was drawn: only uncovered pixels pay for it.
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    m_sky.use();
    const glm::mat4 inverse = glm::inverse(viewProjection);
    const glm::vec3 zenith(0.30f, 0.50f, 0.85f);
    glUniformMatrix4fv(m_skyInvViewProj, 1, GL_FALSE, &inverse[0][0]);
    glUniform3fv(m_skyFog, 1, &light.fogColor[0]);
    glUniform3fv(m_skyZenith, 1, &zenith[0]);
    glUniform3fv(m_skySun, 1, &light.sunDirection[0]);
    glBindVertexArray(m_emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    m_stats.chunks = m_chunks.stats();
    m_stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace render
