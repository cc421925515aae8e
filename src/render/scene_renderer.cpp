#include "render/scene_renderer.h"

#include <chrono>
#include <cmath>
#include <glm/common.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/frustum.h"
#include "world/column_light.h"
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
    : m_atlas(dataDir / "assets" / "atlas.png"), m_chunks(dataDir), m_lines(dataDir), m_entities(dataDir),
      m_hair(dataDir), m_sky(dataDir / "shaders" / "sky.vert", dataDir / "shaders" / "sky.frag") {
    m_skyInvViewProj = m_sky.uniform("uInvViewProj");
    m_skyFog = m_sky.uniform("uFogColor");
    m_skyZenith = m_sky.uniform("uZenithColor");
    m_skySun = m_sky.uniform("uSunDir");
    m_skyMoon = m_sky.uniform("uMoonDir");
    m_skyDiscs = m_sky.uniform("uDiscs");
    glGenVertexArrays(1, &m_emptyVao);
}

std::optional<glm::vec2> SceneRenderer::project(const glm::vec3& world) const {
    const glm::vec4 clip = m_lastViewProjection * glm::vec4(world - m_lastEye, 1.0f);
    if (clip.w <= 0.05f) return std::nullopt;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::vec2((ndc.x * 0.5f + 0.5f) * static_cast<float>(m_lastViewport.x),
                     (0.5f - ndc.y * 0.5f) * static_cast<float>(m_lastViewport.y));
}

void SceneRenderer::drawPendulumSets(const game::GameState& state, const Camera& cam, float alpha) {
    for (const auto& set : state.pendulumSets) {
        m_shapes.clear();
        game::appendPendulumSetShapes(set, alpha, m_shapes);
        // Lit by the light at its post's foot, the block the set stands in.
        const world::LocalLight l = world::lightAt(state.world, set.base());
        m_entities.setLocalLight(l.sun, {l.red, l.green, l.blue});
        for (const game::Shape& shape : m_shapes) m_entities.addShape(shape, cam.eye);
    }
}

void SceneRenderer::render(const game::GameState& state, const Camera& cam, glm::ivec2 viewport,
                           const SceneSettings& settings, float alpha) {
    const auto start = std::chrono::steady_clock::now();
    m_chunks.update(state.world, cam.eye, settings.viewRadius, settings.meshBudgetSeconds, settings.levelOfDetail);

    // The time of day's light; at noon the sun's and sky's colours unscaled.
    const Daylight day = daylightAt(state.day.hours);
    ChunkLighting light;
    light.sunDirection = day.lightDirection;
    light.sunColour = day.lightColour;
    light.skyColour = day.skyColour;
    light.fogColor = day.fogColour;
    const float viewDistance = static_cast<float>(settings.viewRadius * world::kChunkSize);
    light.fogEnd = viewDistance;
    light.fogStart = viewDistance * 0.55f;

    const glm::ivec2 frame = settings.frame.x > 0 && settings.frame.y > 0 ? settings.frame : viewport;
    const float aspect = frame.y > 0 ? static_cast<float>(frame.x) / static_cast<float>(frame.y) : 1.0f;
    const glm::mat4 projection =
        glm::perspective(glm::radians(settings.fovDegrees), aspect, 0.05f, viewDistance + 64.0f);
    const glm::vec3 forward = game::lookDirection(cam.yaw, cam.pitch);
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), forward, glm::vec3(0.0f, 1.0f, 0.0f));
    // A tile: the part of the frame's clip space it covers, stretched over the whole viewport.
    glm::mat4 tile(1.0f);
    if (frame != viewport) {
        const glm::vec2 f(frame), o(settings.tileOrigin), v(viewport);
        const float left = -1.0f + 2.0f * o.x / f.x, right = -1.0f + 2.0f * (o.x + v.x) / f.x;
        const float top = 1.0f - 2.0f * o.y / f.y, bottom = 1.0f - 2.0f * (o.y + v.y) / f.y;
        tile[0][0] = 2.0f / (right - left);
        tile[1][1] = 2.0f / (top - bottom);
        tile[3][0] = -(right + left) / (right - left);
        tile[3][1] = -(top + bottom) / (top - bottom);
    }
    const glm::mat4 viewProjection = tile * projection * view;

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
    // Solid objects first, their back faces culled (spheres and boxes are closed and wound counter-
    // clockwise from outside): near the camera they cover much of the frame, and drawn before the
    // terrain they let the depth test reject the terrain behind them instead of shading it twice.
    drawPendulumSets(state, cam, alpha);
    // Lines wider than a pixel (a screenshot drawn larger, in tiles) may reach past the edge of the
    // view they are clipped to (llvmpipe draws them with a guard band): then no ball is left out.
    const Frustum frustum(viewProjection);
    const Frustum* hairCull = settings.lineWidth > 1.0f ? nullptr : &frustum;
    // The hair moves on its own clock (1/60 s substeps at every tick rate): drawn between its last two.
    const float hairAlpha = game::hairDrawAlpha(state, alpha);
    for (const auto& ball : state.hairBalls) {
        // Lit by the light at its centre (the hair's strands alike: they reach a ball's width or two around it).
        const world::LocalLight l = world::lightAt(state.world, glm::ivec3(glm::floor(ball.centre())));
        m_entities.setLocalLight(l.sun, {l.red, l.green, l.blue});
        m_entities.addShape(game::hairBallShape(ball, alpha), cam.eye);
        m_hair.add(ball, hairAlpha, cam.eye, hairCull, localTint(day, l.sun, {l.red, l.green, l.blue}));
    }
    m_entities.setLocalLight(world::kMaxLight, glm::ivec3(0));
    m_entities.flush(viewProjection, light);
    m_chunks.draw(viewProjection, cam.eye, viewport, m_atlas.arrayTexture(), light, settings.occlusionCulling);
    m_lastViewProjection = projection * view;
    m_lastEye = cam.eye;
    m_lastViewport = settings.labelSpace.x > 0 && settings.labelSpace.y > 0 ? settings.labelSpace : frame;
    glDisable(GL_CULL_FACE);
    glLineWidth(settings.lineWidth);
    // The hair, lit by the light where its ball is (added with its colours). The pendulums' rods are boxes of
    // the solid objects above.
    m_hair.flush(viewProjection);
    m_stats.hairVertices = m_hair.lastVertexCount();
    glEnable(GL_CULL_FACE);

    // Outline of the targeted block (from the simulated eye, as the game uses it for edits).
    if (!state.paused) {
        const game::Target target = game::targetOf(state);
        if (target.kind == game::Target::Kind::Block) {
            const glm::vec3 lo = glm::vec3(target.block.block) - cam.eye - glm::vec3(0.002f);
            m_lines.addBox(lo, lo + glm::vec3(1.004f), glm::vec4(0.05f, 0.05f, 0.05f, 1.0f));
            m_lines.flush(viewProjection);
        }
    }
    glDisable(GL_CULL_FACE);
    glLineWidth(1.0f);

    // Sky last, at the far plane, where nothing else was drawn: only uncovered pixels pay for it.
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    m_sky.use();
    const glm::mat4 inverse = glm::inverse(viewProjection);
    const glm::vec3 discs(day.sunDisc, day.moonDisc, day.stars);
    glUniformMatrix4fv(m_skyInvViewProj, 1, GL_FALSE, &inverse[0][0]);
    glUniform3fv(m_skyFog, 1, &light.fogColor[0]);
    glUniform3fv(m_skyZenith, 1, &day.zenithColour[0]);
    glUniform3fv(m_skySun, 1, &day.sunDirection[0]);
    glUniform3fv(m_skyMoon, 1, &day.moonDirection[0]);
    glUniform3fv(m_skyDiscs, 1, &discs[0]);
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
