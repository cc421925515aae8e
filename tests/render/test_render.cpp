// Render tests: known scenes drawn through OSMesa, the same renderers as the window, compared with
// golden PNGs; plus checks that need no golden (colour where a block must be, determinism).
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "../temp_dir.h"
#include "game/game_state.h"
#include "game/state_io.h"
#include "image_compare.h"
#include "render/chunk_streaming.h"
#include "render/data_dir.h"
#include "render/entity_renderer.h"
#include "render/fragment_counter.h"
#include "render/frustum.h"
#include "render/hair_renderer.h"
#include "render/offscreen.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"
#include "render/shader.h"
#include "save/world_store.h"
#include "ui/hotbar_layout.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"
#include "world/column_light.h"
#include "world/terrain.h"

namespace {

constexpr int kW = 320, kH = 200;

class RenderTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        // MINECRAPPY_GL_BACKEND picks the backend (CTest runs these tests once for each).
        const char* env = std::getenv("MINECRAPPY_GL_BACKEND");
        const auto backend = render::offscreenBackendFromName(env && *env ? env : "auto");
        ASSERT_TRUE(backend.has_value()) << "MINECRAPPY_GL_BACKEND=" << env;
        context = render::makeOffscreenContext(*backend, kW, kH);
        std::printf("render tests on %s\n", std::string(render::currentOffscreenBackend()).c_str());
        scene = std::make_unique<render::SceneRenderer>(render::dataDir());
        imgui = std::make_unique<ui::ImGuiLayer>(nullptr);
    }
    static void TearDownTestSuite() {
        imgui.reset();
        scene.reset();
        context.reset();
    }
    static render::Image draw(const game::GameState& s, bool hud, int viewRadius = 4, bool levelOfDetail = true,
                              float fovDegrees = 70.0f) {
        render::SceneSettings settings;
        settings.fovDegrees = fovDegrees;
        settings.viewRadius = viewRadius;
        settings.levelOfDetail = levelOfDetail;
        settings.meshBudgetSeconds = 0.0;
        scene->render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
        if (hud) {
            imgui->beginFrame({kW, kH}, 1.0f / 60.0f);
            ui::drawHud(s, scene->atlas(), {});
            imgui->endFrame();
        }
        context->present();
        return render::readFramebuffer(kW, kH);
    }
    // A frame of `r` at view radius 6 meshing within `budget` seconds (0: everything at once), as read back.
    static render::Image streamFrame(render::SceneRenderer& r, const game::GameState& s, double budget) {
        render::SceneSettings settings;
        settings.viewRadius = 6;
        settings.meshBudgetSeconds = budget;
        r.render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
        context->present();
        return render::readFramebuffer(kW, kH);
    }
    // Mean colour of a 15x15 box: one pixel could land on a mortar line or a grass speck.
    static glm::ivec3 pixel(const render::Image& img, int cx, int cy) {
        glm::ivec3 sum(0);
        int n = 0;
        for (int y = std::max(cy - 7, 0); y <= std::min(cy + 7, img.height - 1); ++y) {
            for (int x = std::max(cx - 7, 0); x <= std::min(cx + 7, img.width - 1); ++x) {
                const std::size_t i = (static_cast<std::size_t>(y) * img.width + x) * 4;
                sum += glm::ivec3(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]);
                ++n;
            }
        }
        return sum / n;
    }
    // The scene at `size` (view radius 4, meshed whole) with the object labels and the HUD when asked for.
    static render::Image drawWithUi(const game::GameState& s, glm::ivec2 size, bool labels, bool hud) {
        render::SceneSettings settings;
        settings.viewRadius = 4;
        settings.meshBudgetSeconds = 0.0;
        const render::OffscreenTarget target(size);
        scene->render(s, render::interpolatedCamera(s, 1.0f), size, settings);
        imgui->beginFrame(size, 1.0f / 60.0f);
        if (labels) ui::drawObjectLabels(s, *scene, 1.0f);
        if (hud) ui::drawHud(s, scene->atlas(), {});
        imgui->endFrame();
        render::Image image;
        image.width = size.x;
        image.height = size.y;
        image.rgba.resize(static_cast<std::size_t>(size.x) * size.y * 4);
        target.readInto(image, {0, 0}, size);
        return image;
    }
    static inline std::unique_ptr<render::RenderContext> context;
    static inline std::unique_ptr<render::SceneRenderer> scene;
    static inline std::unique_ptr<ui::ImGuiLayer> imgui;
};

game::GameState flatScene() {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    game::GameState s(def);
    // A small arrangement of every block type in front of the camera.
    const world::BlockType types[] = {world::BlockType::Stone, world::BlockType::Brick,  world::BlockType::Planks,
                                      world::BlockType::Log,   world::BlockType::Sand,   world::BlockType::Cobblestone,
                                      world::BlockType::Snow,  world::BlockType::Leaves, world::BlockType::Gravel,
                                      world::BlockType::Dirt};
    int i = 0;
    for (const auto t : types) {
        s.world.set({-5 + i, 33, -6}, t);
        if (i % 2 == 0) s.world.set({-5 + i, 34, -6}, t);
        ++i;
    }
    s.player.position = glm::vec3(0.5f, 33.0f, 0.5f);
    s.player.yaw = 0.0f;
    s.player.pitch = -15.0f;
    s.previousPlayer = s.player;
    return s;
}

TEST_F(RenderTest, FlatSceneMatchesGolden) {
    const auto r = testing_support::compareWithGolden(draw(flatScene(), true), "flat_blocks");
    EXPECT_TRUE(r.ok) << r.message;
}

// The HUD at the smallest frames the tests and --size use: the whole hotbar inside the frame (its slots
// shrink, src/ui/hotbar_layout.h), the block name above it, the crosshair; goldens at 320x180 and 160x90
// (MINECRAPPY_UPDATE_GOLDENS=1 regenerates them; look at each).
TEST_F(RenderTest, TheHudFitsSmallFramesGoldens) {
    const game::GameState s = flatScene();
    for (const glm::ivec2 size : {glm::ivec2(320, 180), glm::ivec2(160, 90)}) {
        render::Image image;
        {
            const render::OffscreenTarget target(size);
            render::SceneSettings settings;
            settings.viewRadius = 4;
            settings.meshBudgetSeconds = 0.0;
            scene->render(s, render::interpolatedCamera(s, 1.0f), size, settings);
            imgui->beginFrame(size, 1.0f / 60.0f);
            ui::drawHud(s, scene->atlas(), {});
            imgui->endFrame();
            image.width = size.x;
            image.height = size.y;
            image.rgba.resize(static_cast<std::size_t>(size.x) * size.y * 4);
            target.readInto(image, {0, 0}, size);
        }
        const std::string name = "hud_" + std::to_string(size.x) + "x" + std::to_string(size.y);
        const auto r = testing_support::compareWithGolden(image, name);
        EXPECT_TRUE(r.ok) << r.message;
    }
}

// Every panel fits the smallest frames (ui/panel_fit.h): at 320x180 and 160x90 each window lies wholly inside
// the display, scrolling what does not fit. At 320x180 the pendulum panel ran 240 px past the right edge,
// its theta and omega columns out of reach. Caught: the settings window without the cap (520 x 560).
TEST_F(RenderTest, PanelFitEveryPanelStaysInsideTheSmallestFrames) {
    game::GameState s = flatScene();
    ASSERT_FALSE(s.pendulumSets.empty());
    ASSERT_FALSE(s.hairBalls.empty());
    ui::PendulumPanel pendulum;
    pendulum.set = &s.pendulumSets[0];
    pendulum.edit = s.pendulumSets[0].def();
    ui::HairPanel hair;
    hair.ball = &s.hairBalls[0];
    hair.edit = s.hairBalls[0].def();
    ui::WorldPanel worlds;
    worlds.folder = std::filesystem::temp_directory_path();
    ui::SettingsPanel settings;
    ui::BlocksPanel blocks;
    const struct {
        const char* window;
        std::function<void()> show;
    } panels[] = {
        {"Blocks", [&] { ui::showBlocksPanel(blocks, s.player, scene->atlas(), nullptr); }},
        {"Pendulum set", [&] { ui::showPendulumPanel(pendulum, nullptr); }},
        {"Hair ball", [&] { ui::showHairPanel(hair, nullptr); }},
        {"Worlds", [&] { ui::showWorldPanel(worlds, nullptr); }},
        {"Settings", [&] { ui::showSettingsPanel(settings, nullptr); }},
        {"Controls (F1)", [&] { ui::showHelpPanel(nullptr); }},
        {"Paused",
         [&] {
             double hours = 18.5;
             ui::PauseMenu menu;
             ui::showPausePanel(hours, menu);
         }},
    };
    // First, as the settings first open: at 640x480 (the smallest window a player is likely to use) the settings'
    // labels fit beside their widgets: nothing scrolls sideways. Catches ImGui's default widget width, which pushed
    // "Tick rate (from the next start)" past the panel's right edge.
    const glm::ivec2 player(640, 480);
    imgui->beginFrame(player, 1.0f / 60.0f);
    imgui->endFrame();
    for (int frame = 0; frame < 3; ++frame) {
        imgui->beginFrame(player, 1.0f / 60.0f);
        ui::showSettingsPanel(settings, nullptr);
        imgui->endFrame();
    }
    const ImGuiWindow* settingsWindow = ImGui::FindWindowByName("Settings");
    ASSERT_NE(settingsWindow, nullptr);
    EXPECT_LE(settingsWindow->Pos.x + settingsWindow->Size.x, 640.0f);
    EXPECT_EQ(settingsWindow->ScrollMax.x, 0.0f)
        << "the settings scroll sideways at 640x480 by " << settingsWindow->ScrollMax.x << " px";
    for (const glm::ivec2 size : {glm::ivec2(320, 180), glm::ivec2(160, 90)}) {
        for (const auto& panel : panels) {
            // A frame without the panel, so that it appears anew at this size; then a few to settle its size.
            imgui->beginFrame(size, 1.0f / 60.0f);
            imgui->endFrame();
            for (int frame = 0; frame < 3; ++frame) {
                imgui->beginFrame(size, 1.0f / 60.0f);
                panel.show();
                imgui->endFrame();
            }
            const ImGuiWindow* w = ImGui::FindWindowByName(panel.window);
            ASSERT_NE(w, nullptr) << panel.window;
            EXPECT_GE(w->Pos.x, 0.0f) << panel.window << " at " << size.x << "x" << size.y;
            EXPECT_GE(w->Pos.y, 0.0f) << panel.window << " at " << size.x << "x" << size.y;
            EXPECT_LE(w->Pos.x + w->Size.x, static_cast<float>(size.x) + 0.5f)
                << panel.window << " at " << size.x << "x" << size.y << ": width " << w->Size.x;
            EXPECT_LE(w->Pos.y + w->Size.y, static_cast<float>(size.y) + 0.5f)
                << panel.window << " at " << size.x << "x" << size.y << ": height " << w->Size.y;
        }
    }
}

// Object labels behind blocks are not drawn (ui::objectLabels, world/raycast.h). Each label's verdict is checked
// against an independent test of its line of sight, sampled every centimetre through the blocks, in the open
// scene, with a stone pillar put across one label's line of sight, and from a pocket 10 blocks underground
// looking up at the objects; and by the picture: the frame drawn with the labels differs from the one drawn
// without them in the open, and is the same byte for byte underground. Catches labels drawn regardless of
// the blocks ("shake" and "exact" floating over a tunnel's rock).
TEST_F(RenderTest, ObjectLabelsBehindBlocksAreHidden) {
    game::GameState s = flatScene();
    const glm::ivec2 size(320, 180);
    const auto frame = [&](bool labels) { return drawWithUi(s, size, labels, false); };
    // The independent verdict: a block at any centimetre of the segment from the eye to the label's point.
    const auto blocked = [&](const ui::ObjectLabel& l) {
        const glm::vec3 eye = render::interpolatedCamera(s, 1.0f).eye;
        const int steps = static_cast<int>(std::ceil(glm::length(l.at - eye) / 0.01f));
        for (int k = 0; k < steps; ++k) {
            const glm::vec3 p = eye + (l.at - eye) * (static_cast<float>(k) / static_cast<float>(steps));
            if (world::isSolid(s.world.get(glm::ivec3(glm::floor(p))))) return true;
        }
        return false;
    };
    const auto check = [&](const char* where) {
        frame(false); // sets the projection the labels use
        const std::vector<ui::ObjectLabel> labels = ui::objectLabels(s, *scene, 1.0f);
        int hidden = 0;
        for (const ui::ObjectLabel& l : labels) {
            EXPECT_EQ(l.hidden, blocked(l)) << where << ": " << l.text << " at " << l.distance << " m";
            hidden += l.hidden ? 1 : 0;
        }
        return std::pair{static_cast<int>(labels.size()), hidden};
    };

    // The scene's row of blocks hides a label or two already.
    const auto [open, openHidden] = check("open");
    ASSERT_GE(open, 4) << "the precondition: the demo scene's labels are in view";
    EXPECT_LT(openHidden, open - 2);
    EXPECT_NE(frame(true).rgba, frame(false).rgba) << "the labels in the open are drawn";

    // A stone pillar halfway along the first visible label's line of sight.
    frame(false);
    const std::vector<ui::ObjectLabel> before = ui::objectLabels(s, *scene, 1.0f);
    const auto first = std::find_if(before.begin(), before.end(), [](const ui::ObjectLabel& l) { return !l.hidden; });
    ASSERT_NE(first, before.end());
    const glm::vec3 mid = 0.5f * (render::interpolatedCamera(s, 1.0f).eye + first->at);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            s.world.set(glm::ivec3(glm::floor(mid)) + glm::ivec3(dx, dy, 0), world::BlockType::Stone);
    const auto [pillar, pillarHidden] = check("behind a pillar");
    EXPECT_GT(pillarHidden, openHidden);
    EXPECT_LT(pillarHidden, pillar) << "the pillar hides some labels, not all";

    // 10 blocks underground, in a pocket of air, looking up at the objects.
    s.player.position = glm::vec3(0.5f, static_cast<float>(world::kFlatSurface - 10), 2.5f);
    s.player.pitch = 35.0f;
    s.previousPlayer = s.player;
    for (int y = 0; y < 3; ++y) s.world.set(glm::ivec3(0, world::kFlatSurface - 10 + y, 2), world::BlockType::Air);
    const auto [under, underHidden] = check("underground");
    ASSERT_GE(under, 1) << "the precondition: labels project into the view from underground";
    EXPECT_EQ(underHidden, under);
    EXPECT_EQ(frame(true).rgba, frame(false).rgba) << "a label underground is drawn";
}

// At 160x90 the object labels keep clear of the HUD: the rows of the block name and the hotbar are the same byte
// for byte with the labels drawn and without them, while the labels do show above (the demo's labels fall on
// those rows at full size: "euler" printed over "grass"). Catches labels laid out over the whole frame.
TEST_F(RenderTest, ObjectLabelsKeepClearOfTheHudInASmallFrame) {
    game::GameState s = flatScene();
    const glm::ivec2 size(160, 90);
    // The block name's top: the font's 13 px line 6 px above the hotbar (the image's rows run top down).
    const int hudTop = static_cast<int>(ui::hotbarLayout(glm::vec2(size)).corner[0].y) - 13 - 6;
    ASSERT_GT(hudTop, 20);
    // The precondition: a pitch at which a label's point in sight falls on the HUD's rows.
    bool onHud = false;
    for (float pitch = -30.0f; pitch <= 30.0f && !onHud; pitch += 1.0f) {
        s.player.pitch = pitch;
        s.previousPlayer = s.player;
        drawWithUi(s, size, false, false); // sets the projection the labels use
        for (const ui::ObjectLabel& l : ui::objectLabels(s, *scene, 1.0f))
            onHud |= !l.hidden && l.screen.y > static_cast<float>(hudTop) && l.screen.y < static_cast<float>(size.y);
    }
    ASSERT_TRUE(onHud) << "no pitch puts a label on the HUD";
    const render::Image with = drawWithUi(s, size, true, true), without = drawWithUi(s, size, false, true);
    const std::size_t rowBytes = static_cast<std::size_t>(size.x) * 4;
    const auto rows = [&](const render::Image& im, int from, int to) {
        return std::vector<std::uint8_t>(im.rgba.begin() + static_cast<std::ptrdiff_t>(from * rowBytes),
                                         im.rgba.begin() + static_cast<std::ptrdiff_t>(to * rowBytes));
    };
    int firstDiffering = -1;
    for (int y = size.y - 1; y >= hudTop; --y)
        if (rows(with, y, y + 1) != rows(without, y, y + 1)) firstDiffering = y;
    EXPECT_EQ(firstDiffering, -1) << "a label printed over the HUD (row " << firstDiffering << "; the HUD from row "
                                  << hudTop << ")";
    EXPECT_NE(rows(with, 0, hudTop), rows(without, 0, hudTop)) << "the precondition: labels show above the HUD";
}

TEST_F(RenderTest, DefaultTerrainMatchesGolden) {
    game::GameState s(game::GameDef{});
    const auto r = testing_support::compareWithGolden(draw(s, false), "default_terrain");
    EXPECT_TRUE(r.ok) << r.message;
}

// Luminance (Rec. 709 weights on the stored bytes), 0..255: of a colour, and the mean of a frame's.
double luminance(glm::ivec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
double meanLuminance(const render::Image& img) {
    double sum = 0.0;
    for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4)
        sum += luminance({img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]});
    return sum / (static_cast<double>(img.rgba.size()) / 4.0);
}

// Puts `t` on the first air over the ground at three places beside the first pendulum set's post (where the
// night-with-lamps golden shows its lamps); returns how many it placed.
int besideThePost(game::GameState& s, world::BlockType t) {
    if (s.pendulumSets.empty()) return 0;
    const glm::ivec3 post = s.pendulumSets[0].base();
    int placed = 0;
    for (const int dx : {-2, 2, 4}) {
        glm::ivec3 at = post + glm::ivec3(dx, -4, 0); // up to the first air over ground
        while (at.y < post.y + 4 &&
               !(s.world.get(at) == world::BlockType::Air && world::isSolid(s.world.get(at - glm::ivec3(0, 1, 0)))))
            ++at.y;
        if (s.world.get(at) == world::BlockType::Air) s.world.set(at, t), ++placed;
    }
    return placed;
}

// The default view at noon, at dusk (17:30, the sun low in the west) and at midnight, against goldens on each
// backend; default_terrain above is the noon golden. Measured mean luminance on llvmpipe (both backends): noon
// 96.2, dusk 56.3, midnight 11.7 (night / noon 0.122). Held: midnight under a fifth of noon (the moonlit sky is
// about a sixth of noon's sky light, daylight.cpp), dusk between the two and redder than noon. Mutation caught: a
// sky light that ignores the time (uSkyColour left at 1): night / noon 0.68.
TEST_F(RenderTest, NightIsDarkerThanNoonAndDuskIsBetweenAndRedder) {
    game::GameState s(game::GameDef{});
    ASSERT_EQ(s.day.hours, game::kDefaultHours); // precondition: the goldens' noon is the default time
    const render::Image noon = draw(s, false);
    s.day.hours = 17.5;
    const render::Image dusk = draw(s, false);
    auto r = testing_support::compareWithGolden(dusk, "default_terrain_dusk");
    EXPECT_TRUE(r.ok) << r.message;
    s.day.hours = 0.0;
    const render::Image night = draw(s, false);
    r = testing_support::compareWithGolden(night, "default_terrain_night");
    EXPECT_TRUE(r.ok) << r.message;
    // Night with lamps: three on the ground beside the pendulum set's post, glowing and lighting the ground.
    ASSERT_EQ(besideThePost(s, world::BlockType::Lamp), 3); // precondition: the golden shows three lamps
    r = testing_support::compareWithGolden(draw(s, false), "default_terrain_night_lamps");
    EXPECT_TRUE(r.ok) << r.message;
    const double lNoon = meanLuminance(noon), lDusk = meanLuminance(dusk), lNight = meanLuminance(night);
    std::printf("mean luminance: noon %.1f, dusk %.1f, midnight %.1f (night / noon %.3f)\n", lNoon, lDusk, lNight,
                lNight / lNoon);
    EXPECT_LT(lNight, 0.2 * lNoon);
    EXPECT_GT(lDusk, lNight);
    EXPECT_LT(lDusk, lNoon);
    const auto redness = [](const render::Image& img) {
        double r = 0.0, b = 0.0;
        for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) r += img.rgba[i], b += img.rgba[i + 2];
        return r / std::max(b, 1.0);
    };
    EXPECT_GT(redness(dusk), redness(noon));
}

// A lamp is drawn at its own full colour at midnight, where the sky's light leaves other blocks dark: the ground
// under the player (looking straight down) as a lamp and as stone. Measured on llvmpipe: the 15x15 box at the
// crosshair (glowing panes and dark frame bars) has mean luminance 68.1 over the lamp, 21.2 over stone (3.2
// times). Held: at least twice, a factor of 1.6 under the measurement. Mutation caught: the lamp shaded like
// any block (the shader's emissive test removed): 9.3, 0.4 times stone's.
TEST_F(RenderTest, ALampGlowsAtMidnight) {
    game::GameState s = flatScene();
    s.day.hours = 0.0;
    s.player.pitch = -89.0f;
    s.previousPlayer = s.player;
    s.world.set({0, 32, 0}, world::BlockType::Lamp);
    const double lamp = luminance(pixel(draw(s, false), kW / 2, kH / 2));
    s.world.set({0, 32, 0}, world::BlockType::Stone);
    const double stone = luminance(pixel(draw(s, false), kW / 2, kH / 2));
    std::printf("midnight: lamp %.1f, stone %.1f (%.1f times)\n", lamp, stone, lamp / stone);
    EXPECT_GT(lamp, 2.0 * stone);
}

// A lamp lights the ground around it at night. The default view at midnight with three lamps beside the post,
// against the same view with stone blocks in their place, over the pixels that are neither (those that differ
// between the two at noon, where the sun outshines the lamps' light, are the blocks themselves: left out).
// Measured on llvmpipe: mean luminance 33.3 with lamps, 11.7 with stone (2.85 times) over 95 % of the frame.
// Held: at least 1.9 times, the measured gain over 1 halved. Mutation caught: block light left out of the chunk
// shader's light: 1.26 times (the hair and the pendulum set are still lit by the lamps).
TEST_F(RenderTest, ALampLightsItsSurroundingsAtNight) {
    const auto scene = [&](world::BlockType t, double hours) {
        game::GameState s(game::GameDef{});
        EXPECT_EQ(besideThePost(s, t), 3); // precondition: three blocks placed
        s.day.hours = hours;
        return draw(s, false);
    };
    const render::Image lampsNoon = scene(world::BlockType::Lamp, 12.0),
                        stoneNoon = scene(world::BlockType::Stone, 12.0);
    const render::Image lamps = scene(world::BlockType::Lamp, 0.0), stone = scene(world::BlockType::Stone, 0.0);
    double withLamps = 0.0, withStone = 0.0;
    std::size_t around = 0, pixels = lamps.rgba.size() / 4;
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::size_t at = 4 * i;
        if (!std::equal(&lampsNoon.rgba[at], &lampsNoon.rgba[at] + 3, &stoneNoon.rgba[at])) continue; // the blocks
        const auto lum = [&](const render::Image& img) {
            return luminance({img.rgba[at], img.rgba[at + 1], img.rgba[at + 2]});
        };
        withLamps += lum(lamps);
        withStone += lum(stone);
        ++around;
    }
    ASSERT_GT(around, pixels / 2); // precondition: most of the frame is neither block
    withLamps /= static_cast<double>(around);
    withStone /= static_cast<double>(around);
    std::printf("midnight, around the blocks (%.0f %% of the frame): lamps %.1f, stone %.1f (%.2f times)\n",
                100.0 * static_cast<double>(around) / static_cast<double>(pixels), withLamps, withStone,
                withLamps / withStone);
    EXPECT_GT(withLamps, 1.9 * withStone);
}

// Ground under a roof is darker than open ground at noon: the player stands under a 13 x 13 roof of planks two
// blocks over the flat world's grass, looking straight down. Measured on llvmpipe: crosshair luminance 35.1 under
// the roof, 143.2 without it (0.25 times). Held: at most 0.5 times, twice the measurement. Mutation caught: the
// sky's and the sun's light not scaled by sunlight (the shader's sunLevel left at 1): 1.00 times.
TEST_F(RenderTest, GroundUnderARoofIsDarkerThanOpenGroundAtNoon) {
    game::GameState s = flatScene();
    s.player.pitch = -89.0f;
    s.previousPlayer = s.player;
    const double open = luminance(pixel(draw(s, false), kW / 2, kH / 2));
    for (int z = -6; z <= 6; ++z)
        for (int x = -6; x <= 6; ++x) s.world.set({x, 36, z}, world::BlockType::Planks);
    const double roofed = luminance(pixel(draw(s, false), kW / 2, kH / 2));
    std::printf("noon: ground under the roof %.1f, in the open %.1f (%.2f times)\n", roofed, open, roofed / open);
    EXPECT_LT(roofed, 0.5 * open);
}

TEST_F(RenderTest, PlacedBrickShowsRedAtTheCrosshair) {
    game::GameState s = flatScene();
    s.player.pitch = -89.0f;
    s.previousPlayer = s.player;
    const auto before = pixel(draw(s, false), kW / 2, kH / 2);
    EXPECT_GT(before.g, before.r);                    // grass underfoot
    s.world.set({0, 32, 0}, world::BlockType::Brick); // replace the grass under the player
    const auto after = pixel(draw(s, false), kW / 2, kH / 2);
    EXPECT_GT(after.r, after.g + 30) << after.r << " " << after.g << " " << after.b;
}

TEST_F(RenderTest, SameStateSamePixels) {
    const auto a = draw(flatScene(), true);
    const auto b = draw(flatScene(), true);
    EXPECT_EQ(a.rgba, b.rgba);
}

// The default world seen from 24 blocks above the spawn, looking over the hills to the horizon.
game::GameState overviewState() {
    game::GameState s(game::GameDef{});
    s.player.position.y += 24.0f;
    s.player.yaw = 200.0f;
    s.player.pitch = -12.0f;
    s.previousPlayer = s.player;
    return s;
}

// The level of detail (coarse cells beyond 4 chunks) must not change the picture much: the share of
// visibly different pixels stays under 1% in the demo view at the default view radius and in a view
// over the hills to the horizon, while the frame draws fewer triangles.
TEST_F(RenderTest, FarLevelOfDetailChangesFewPixels) {
    game::GameState demo(game::GameDef{});
    game::GameState overview = overviewState();
    for (const auto* view : {&demo, &overview}) {
        const render::Image full = draw(*view, false, 8, false);
        const long long fullTriangles = scene->stats().chunks.triangles;
        const render::Image coarse = draw(*view, false, 8, true);
        const long long coarseTriangles = scene->stats().chunks.triangles;
        EXPECT_LT(coarseTriangles, fullTriangles) << "precondition: the level of detail is in use";
        const auto r = testing_support::compareImages(coarse, full);
        std::printf("%s: %lld -> %lld triangles, %.2f%% of pixels visibly different, mean |diff| %.2f\n",
                    view == &demo ? "demo view" : "overview", fullTriangles, coarseTriangles, 100.0 * r.badPixelShare,
                    r.meanAbsDiff);
        const std::string name = view == &demo ? "lod_demo" : "lod_overview"; // for a person to compare
        std::filesystem::create_directories(MC_RENDER_OUT);
        render::writePng(full, std::filesystem::path(MC_RENDER_OUT) / (name + ".full.png"));
        render::writePng(coarse, std::filesystem::path(MC_RENDER_OUT) / (name + ".coarse.png"));
        EXPECT_LT(r.badPixelShare, 0.01);
    }
}

// The ground stays at its height across the level-of-detail boundaries: on flat terrain (the top block at y 32,
// one block into a chunk) cells solid to their top would stand one block (2-cells) and three (4-cells) above
// the ground, their side faces a brown line across the view at each boundary. Each row's mean luminance, looking
// along the ground to the horizon at view radius 12 (boundaries at 4 and 8 chunks), with and without the level
// of detail. Measured on llvmpipe: every row equal (largest difference 0.00). Held: no row off by more than 2
// (a tenth of the step's). Mutation caught: cells solid to their top (the old rule): a row off by 26.2.
TEST_F(RenderTest, FlatGroundHasNoStepAtTheLevelOfDetailBoundaries) {
    game::GameState s = flatScene();
    s.player.pitch = -2.0f;
    s.previousPlayer = s.player;
    (void)draw(s, false, 8, true);
    const int drawnWithin8 = scene->stats().chunks.drawn;
    const render::Image coarse = draw(s, false, 12, true);
    // Precondition: chunks beyond 8 (4-cells) are in view, so both boundaries are (flat ground meshes to as many
    // triangles at any level: the counts cannot tell).
    ASSERT_GT(scene->stats().chunks.drawn, drawnWithin8);
    const render::Image fine = draw(s, false, 12, false);
    const auto rowMean = [](const render::Image& img, int y) {
        double sum = 0.0;
        for (int x = 0; x < img.width; ++x) {
            const std::size_t i = (static_cast<std::size_t>(y) * img.width + x) * 4;
            sum += luminance({img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]});
        }
        return sum / img.width;
    };
    double worst = 0.0;
    int worstRow = -1;
    for (int y = 0; y < kH; ++y) {
        const double d = std::abs(rowMean(coarse, y) - rowMean(fine, y));
        if (d > worst) worst = d, worstRow = y;
    }
    std::printf("flat ground, radius 12: rows differ by up to %.2f (row %d)\n", worst, worstRow);
    EXPECT_LE(worst, 2.0) << "row " << worstRow;
}

// A lamp far away at night stays visible at every level of detail, also when another block comes first in its
// cell: lamps on flat ground 180 m (2-cells) and 300 m (4-cells) ahead, each with a stone block beside it, seen
// through a 10 degree field of view. The brightest pixel of a 21x21 box around the lamp with the level of
// detail, against the same without it and against stone in the lamp's place (the lamp's light on the ground
// only). Measured on llvmpipe: 43.5 and 46.6 with the level of detail, 41.8 and 43.7 without, 25.6 and 24.9 for
// stone. Held: at least 0.8 times the picture without it. Mutation caught: the cell of its first block's type
// (the old rule): 25.6 and 24.9, the glow without the lamp.
TEST_F(RenderTest, AFarLampStaysVisibleAtEveryLevelOfDetail) {
    for (const int metres : {180, 300}) {
        const auto scene = [&](world::BlockType t, bool levelOfDetail) {
            game::GameState s = flatScene();
            s.day.hours = 0.0;
            const glm::ivec3 lamp(1, 33, -metres + 1); // the last block of its cell's layer (cells start even)
            s.world.set(lamp, t);
            s.world.set(lamp - glm::ivec3(1, 0, 1), world::BlockType::Stone); // the first
            const glm::vec3 eye = game::eyePosition(s.player);
            const glm::vec3 to = glm::vec3(lamp) + glm::vec3(0.5f) - eye;
            s.player.yaw = glm::degrees(std::atan2(to.x, -to.z));
            s.player.pitch = glm::degrees(std::atan2(to.y, std::sqrt(to.x * to.x + to.z * to.z)));
            s.previousPlayer = s.player;
            const render::Image img = draw(s, false, metres / world::kChunkSize + 1, levelOfDetail, 10.0f);
            double brightest = 0.0;
            for (int y = kH / 2 - 10; y <= kH / 2 + 10; ++y)
                for (int x = kW / 2 - 10; x <= kW / 2 + 10; ++x) {
                    const std::size_t i = (static_cast<std::size_t>(y) * kW + x) * 4;
                    brightest = std::max(brightest, luminance({img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]}));
                }
            return brightest;
        };
        const double coarse = scene(world::BlockType::Lamp, true), fine = scene(world::BlockType::Lamp, false),
                     glowOnly = scene(world::BlockType::Stone, true);
        std::printf("lamp %d m away at midnight, brightest: level of detail %.1f, none %.1f, stone there %.1f\n",
                    metres, coarse, fine, glowOnly);
        EXPECT_GT(fine, 1.5 * glowOnly) << "precondition: the lamp itself shows without the level of detail";
        EXPECT_GT(coarse, 0.8 * fine) << metres << " m";
    }
}

// Coloured light in the level of detail: a red lamp on flat ground at night 180 m ahead (2-cells; from the 4-cells
// on its glow is lost in the fog), seen through a 10 degree field of view. What the lamp's light adds to the frame (the
// picture less the one with stone in its place, channel by channel, the lamp's own tiles left out) is red with the
// level of detail as without it. Measured on llvmpipe: the red share of what it adds 1.00 with the level of detail and
// without it; a white lamp's 0.53. Held: 0.2 over the white lamp's and within 0.1 of the picture without it. Mutation
// caught: the level of detail's flat light keeping only the brightest channel, as white (tried: 0.53, the white
// lamp's).
TEST_F(RenderTest, AFarColouredLampKeepsItsColourAtEveryLevelOfDetail) {
    constexpr int metres = 180;
    const auto scene = [&](world::BlockType t, bool levelOfDetail) {
        game::GameState s = flatScene();
        s.day.hours = 0.0;
        const glm::ivec3 lamp(1, 33, -metres + 1);
        s.world.set(lamp, t);
        const glm::vec3 eye = game::eyePosition(s.player);
        const glm::vec3 to = glm::vec3(lamp) + glm::vec3(0.5f) - eye;
        s.player.yaw = glm::degrees(std::atan2(to.x, -to.z));
        s.player.pitch = glm::degrees(std::atan2(to.y, std::sqrt(to.x * to.x + to.z * to.z)));
        s.previousPlayer = s.player;
        return draw(s, false, metres / world::kChunkSize + 1, levelOfDetail, 10.0f);
    };
    // The red share of what a lamp of type t adds to the box.
    const auto redShare = [&](world::BlockType t, bool levelOfDetail) {
        const render::Image lit = scene(t, levelOfDetail), dark = scene(world::BlockType::Stone, levelOfDetail);
        glm::dvec3 added(0.0);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                if (std::abs(x - kW / 2) <= 12 && std::abs(y - kH / 2) <= 12) continue; // the lamp's own tiles
                const std::size_t i = (static_cast<std::size_t>(y) * kW + x) * 4;
                for (int c = 0; c < 3; ++c) added[c] += std::max(0, int(lit.rgba[i + c]) - int(dark.rgba[i + c]));
            }
        return added.r / std::max(added.r + added.g + added.b, 1.0);
    };
    const double coarse = redShare(world::BlockType::RedLamp, true), fine = redShare(world::BlockType::RedLamp, false),
                 white = redShare(world::BlockType::Lamp, true);
    std::printf("red lamp %d m away at midnight, red share of its light: level of detail %.2f, none %.2f; "
                "white lamp %.2f\n",
                metres, coarse, fine, white);
    EXPECT_GT(white, 0.2) << "precondition: the white lamp's light reaches the frame (a share of 0 is none)";
    EXPECT_LT(white, 0.6) << "precondition: a white lamp's light is not red";
    EXPECT_GT(coarse, white + 0.2) << metres << " m";
    EXPECT_NEAR(coarse, fine, 0.1) << metres << " m";
}

// Three coloured lamps meeting on a wall at night (golden: coloured_lamps_wall.png): red, green and blue lamps
// three blocks apart, two blocks in front of a stone wall, on flat ground at midnight. Where red and green meet
// the wall turns yellow, where green and blue meet it turns cyan. Checked besides the golden: the frame holds
// yellow pixels (red and green each over 1.5 times blue) and cyan ones (green and blue over 1.2 times red);
// measured 16,861 and 10,424 on llvmpipe; held at half of each (8,000 and 5,000).
game::GameState colouredWallScene() {
    game::GameState s = flatScene();
    s.day.hours = 0.0;
    for (int y = 33; y <= 39; ++y)
        for (int x = -7; x <= 8; ++x) s.world.set({x, y, 9}, world::BlockType::Stone);
    s.world.set({-2, 33, 7}, world::BlockType::RedLamp);
    s.world.set({1, 33, 7}, world::BlockType::GreenLamp);
    s.world.set({4, 33, 7}, world::BlockType::BlueLamp);
    s.player.yaw = 180.0f; // south, away from the scene's other blocks
    s.player.pitch = 0.0f;
    s.previousPlayer = s.player;
    return s;
}

TEST_F(RenderTest, ThreeColouredLampsMeetOnAWallAtNightGolden) {
    const render::Image img = draw(colouredWallScene(), false);
    int yellow = 0, cyan = 0;
    for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
        const int r = img.rgba[i], g = img.rgba[i + 1], b = img.rgba[i + 2];
        yellow += 2 * r > 3 * b + 8 && 2 * g > 3 * b + 8;
        cyan += 5 * g > 6 * r + 8 && 5 * b > 6 * r + 8;
    }
    std::printf("coloured lamps on a wall at midnight: %d yellow pixels, %d cyan\n", yellow, cyan);
    EXPECT_GT(yellow, 8000);
    EXPECT_GT(cyan, 5000);
    const auto r = testing_support::compareWithGolden(img, "coloured_lamps_wall");
    EXPECT_TRUE(r.ok) << r.message;
}

// A world with coloured lamps saves and reopens to the same picture: the wall scene above, saved to a world file
// and loaded into a new state, has the saved state hash and draws byte for byte the frame the saved state drew.
// Precondition: that frame differs from the scene with white lamps in the same places (the colour is in it).
// Mutation caught: a loader that takes the coloured lamps for white ones (the picture differs; tried by loading
// every lamp id as the white lamp's).
TEST_F(RenderTest, AWorldWithColouredLampsSavesAndReopensToTheSamePicture) {
    // The scene's blocks were set by hand across the demo objects' room: without them it is a state the game
    // could reach (the save refuses any other).
    const auto scene = [] {
        game::GameState s = colouredWallScene();
        s.pendulumSets.clear();
        s.hairBalls.clear();
        return s;
    };
    const game::GameState s = scene();
    const render::Image saved = draw(s, false);
    game::GameState white = scene();
    for (const int x : {-2, 1, 4}) white.world.set({x, 33, 7}, world::BlockType::Lamp);
    ASSERT_NE(draw(white, false).rgba, saved.rgba);
    const std::filesystem::path dir = test_util::freshRandomTempDir("mc_render_", "coloured_lamps");
    const std::filesystem::path file = dir / "lamps.mcworld";
    save::WorldStore::open(file, true)->save(save::takeSnapshot(s));
    const game::GameState loaded = save::restore(save::WorldStore::open(file, false)->load());
    std::filesystem::remove_all(dir);
    EXPECT_EQ(game::stateHash(loaded), game::stateHash(s));
    EXPECT_EQ(draw(loaded, false).rgba, saved.rgba);
}

// A coloured lamp in a cave at noon (golden: coloured_lamp_cave.png): an orange lamp in a closed stone room
// under the flat world's ground, the player inside looking at it. The sun does not reach in: the room is lit
// orange (red over green over blue in the frame's sum, measured 0.72 / 0.17 / 0.10 of it on llvmpipe; held: in
// that order, red over 0.6, the measured less a sixth).
TEST_F(RenderTest, AColouredLampInACaveAtNoonGolden) {
    game::GameState s = flatScene();
    s.day.hours = 12.0;
    for (int y = 20; y <= 27; ++y)
        for (int z = -8; z <= 4; ++z)
            for (int x = -6; x <= 6; ++x) {
                const bool wall = y == 20 || y == 27 || z == -8 || z == 4 || x == -6 || x == 6;
                s.world.set({x, y, z}, wall ? world::BlockType::Stone : world::BlockType::Air);
            }
    s.world.set({0, 22, -5}, world::BlockType::OrangeLamp);
    s.player.position = glm::vec3(0.5f, 21.0f, 1.5f);
    s.player.yaw = 0.0f;
    s.player.pitch = -10.0f;
    s.previousPlayer = s.player;
    const render::Image img = draw(s, false);
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4)
        sum += glm::dvec3(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]);
    const glm::dvec3 share = sum / (sum.r + sum.g + sum.b);
    std::printf("orange lamp in a cave at noon: red %.2f, green %.2f, blue %.2f of the light\n", share.r, share.g,
                share.b);
    EXPECT_GT(share.r, share.g);
    EXPECT_GT(share.g, share.b);
    EXPECT_GT(share.r, 0.6);
    const auto r = testing_support::compareWithGolden(img, "coloured_lamp_cave");
    EXPECT_TRUE(r.ok) << r.message;
}

// Streaming (the worker thread plus this thread's 2 ms a frame) must end at exactly the picture that
// meshing everything at once gives, also when a block is edited while chunks are still in flight.
TEST_F(RenderTest, StreamedChunksEndAtTheSynchronousPicture) {
    game::GameState s(game::GameDef{});
    const glm::ivec3 eye(glm::floor(s.player.position));
    const auto frame = [&](render::SceneRenderer& r, double budget) { return streamFrame(r, s, budget); };
    render::SceneRenderer streamed(render::dataDir());
    int frames = 0;
    frame(streamed, 0.002);
    ASSERT_GT(streamed.stats().chunks.pending, 0) << "precondition: one frame does not mesh everything";
    // Let the worker finish what it was given (its results wait for the next frame), then edit: pillars
    // of brick 40-60 blocks out in every direction, so some stand in view in chunks the worker has
    // meshed from the old blocks. Those meshes must never be shown.
    streamed.waitForMeshWorker();
    for (const glm::ivec2 d : {glm::ivec2(0, -48), glm::ivec2(0, 48), glm::ivec2(-48, 0), glm::ivec2(48, 0),
                               glm::ivec2(-40, -40), glm::ivec2(40, -40), glm::ivec2(-40, 40), glm::ivec2(40, 40)}) {
        const int x = eye.x + d.x, z = eye.z + d.y;
        const int top = world::surfaceHeight(s.world.terrain(), x, z);
        for (int y = top; y < top + 24; ++y) s.world.set({x, y, z}, world::BlockType::Brick);
    }
    s.world.set(eye + glm::ivec3(0, 1, -4), world::BlockType::Brick); // and one in the nearest chunk
    render::Image last;
    while (frames < 1000) {
        last = frame(streamed, 1e-9); // one light region a frame here: more than one frame on any machine
        ++frames;
        if (streamed.stats().chunks.pending == 0) break;
    }
    ASSERT_EQ(streamed.stats().chunks.pending, 0) << "streaming never completed";
    EXPECT_GT(frames, 1);
    last = frame(streamed, 0.002); // results the worker finished after the last check are applied too
    render::SceneRenderer synchronous(render::dataDir());
    const render::Image all = frame(synchronous, 0.0);
    EXPECT_EQ(synchronous.stats().chunks.pending, 0);
    EXPECT_TRUE(last.rgba == all.rgba) << "streamed picture differs after " << frames
                                       << " frames: " << testing_support::compareImages(last, all).badPixelShare * 100.0
                                       << "% of pixels";
}

// The order chunks stream in (ChunkStreaming::orderCandidates), checked against its rules computed here: every
// light region's candidates one after another, regions by the squared distance of their column nearest the
// camera's (the least over the region's columns, by brute force), within a region each column's chunks one after
// another, columns nearest first, and a column's chunks by height difference. Candidates of 13 x 13 columns
// around a camera off the region grid, shuffled. Mutations caught: the region's coordinates left out of the key
// (regions at one distance interleave); the column distance before the region's (regions split).
TEST(ChunkStreamingOrder, RegionByRegionNearestFirst) {
    using render::ChunkStreaming;
    const world::ChunkCoord centre{5, 2, -3};
    std::vector<ChunkStreaming::Candidate> candidates;
    for (int dz = -6; dz <= 6; ++dz)
        for (int dx = -6; dx <= 6; ++dx)
            for (int y = 0; y < world::kWorldHeightChunks; ++y) {
                const int dy = y - centre.y;
                candidates.push_back(
                    {(dx * dx + dz * dz) * ChunkStreaming::kHeights + dy * dy, {centre.x + dx, y, centre.z + dz}});
            }
    std::shuffle(candidates.begin(), candidates.end(), std::mt19937(46));
    std::vector<ChunkStreaming::CandidateKey> scratch;
    ChunkStreaming::orderCandidates(centre, candidates, scratch);
    ASSERT_EQ(candidates.size(), std::size_t{13 * 13 * world::kWorldHeightChunks});
    const auto regionDistance = [&](world::ChunkCoord c) {
        const world::ChunkCoord r = world::lightRegionOf(c);
        int best = 1 << 30;
        for (int z = 0; z < world::kLightRegion; ++z)
            for (int x = 0; x < world::kLightRegion; ++x) {
                const int dx = r.x * world::kLightRegion + x - centre.x, dz = r.z * world::kLightRegion + z - centre.z;
                best = std::min(best, dx * dx + dz * dz);
            }
        return best;
    };
    const auto sameColumn = [](world::ChunkCoord a, world::ChunkCoord b) { return a.x == b.x && a.z == b.z; };
    std::vector<std::pair<int, int>> regionsDone, columnsDone;
    int regions = 0;
    for (std::size_t i = 1; i < candidates.size(); ++i) {
        const world::ChunkCoord a = candidates[i - 1].second, b = candidates[i].second;
        const world::ChunkCoord ra = world::lightRegionOf(a), rb = world::lightRegionOf(b);
        const int da = candidates[i - 1].first, db = candidates[i].first;
        SCOPED_TRACE("candidate " + std::to_string(i));
        if (ra.x != rb.x || ra.z != rb.z) { // a region ends: it never comes back, and the next is no nearer
            regionsDone.emplace_back(ra.x, ra.z);
            ++regions;
            ASSERT_EQ(std::count(regionsDone.begin(), regionsDone.end(), std::pair(rb.x, rb.z)), 0);
            ASSERT_LE(regionDistance(a), regionDistance(b));
        } else if (!sameColumn(a, b)) { // a column ends within a region: the next is no nearer
            columnsDone.emplace_back(a.x, a.z);
            ASSERT_EQ(std::count(columnsDone.begin(), columnsDone.end(), std::pair(b.x, b.z)), 0);
            ASSERT_LE(da / ChunkStreaming::kHeights, db / ChunkStreaming::kHeights);
        } else { // within a column: nearest height first
            ASSERT_LE(da % ChunkStreaming::kHeights, db % ChunkStreaming::kHeights);
        }
    }
    EXPECT_GE(regions, 40); // precondition: 13 x 13 columns span 7 x 7 regions
}

// An edit changes the light of chunks beyond those meshed at once on the render thread; the worker remeshes
// them, and any still waiting after render::ChunkStreaming::kLateFrames updates are meshed on the render thread.
// So kLateFrames + 1 updates after the edits every chunk in range shows its current blocks and light, whatever
// the worker managed, and the picture is the one a renderer meshing everything at once draws. Lamps go on the
// ground in every chunk column 2 to 6 columns out: 160 lamps, 370 chunks waiting after the first update. Run
// twice: with the worker held (it starts no job: SceneRenderer::holdMeshWorker), so that what the render thread
// does not mesh within its budget is completed late whatever the machine's speed (about 330 chunks here), and
// with the worker running (how many it meshes in time depends on the machine: only the picture is checked).
// Mutation caught: completeLate() left out (chunks still pending after three updates, and the picture differs).
TEST_F(RenderTest, AfterAnEditEveryMeshIsCurrentWithinTheLateFrames) {
    for (const bool held : {true, false}) {
        SCOPED_TRACE(held ? "worker held" : "worker running");
        game::GameState s(game::GameDef{});
        const world::ChunkCoord centre = world::chunkOf(glm::ivec3(glm::floor(s.player.position)));
        const auto frame = [&](render::SceneRenderer& r, double budget) { return streamFrame(r, s, budget); };
        render::SceneRenderer streamed(render::dataDir());
        frame(streamed, 0.0);
        ASSERT_EQ(streamed.stats().chunks.pending, 0); // precondition: everything meshed before the edits
        streamed.holdMeshWorker(held);
        int lamps = 0;
        for (int dz = -6; dz <= 6; ++dz)
            for (int dx = -6; dx <= 6; ++dx) {
                if (std::max(std::abs(dx), std::abs(dz)) < 2) continue;
                const int x = (centre.x + dx) * world::kChunkSize + 16, z = (centre.z + dz) * world::kChunkSize + 16;
                s.world.set({x, world::surfaceHeight(s.world.terrain(), x, z) + 1, z}, world::BlockType::Lamp);
                ++lamps;
            }
        int completedLate = 0, stale = 0, byWorker = 0;
        render::Image last;
        // Held, the budget is as good as none (the chunks near the edits are meshed at once anyway): what is left
        // is completed late on any machine. Running, 2 ms as in play.
        for (int k = 0; k <= render::ChunkStreaming::kLateFrames; ++k) {
            last = frame(streamed, held ? 1e-9 : 0.002);
            completedLate += streamed.stats().chunks.completedLate;
            byWorker += streamed.stats().chunks.meshedByWorker;
            stale = std::max(stale, streamed.stats().chunks.stale);
        }
        std::printf("%s, %d lamps: up to %d chunks stale, %d meshed by the worker, %d completed on the render "
                    "thread after %d frames\n",
                    held ? "held" : "running", lamps, stale, byWorker, completedLate,
                    render::ChunkStreaming::kLateFrames);
        if (held) {
            EXPECT_EQ(byWorker, 0);      // precondition: the hold holds
            EXPECT_GT(completedLate, 0); // precondition: the budget left chunks for the late frames
        }
        EXPECT_EQ(streamed.stats().chunks.pending, 0);
        render::SceneRenderer synchronous(render::dataDir());
        const render::Image all = frame(synchronous, 0.0);
        EXPECT_TRUE(last.rgba == all.rgba)
            << testing_support::compareImages(last, all).badPixelShare * 100.0 << "% of pixels differ";
    }
}

// Moves the player `metres` east of the spawn, standing on the ground there.
void standEastOfSpawn(game::GameState& s, float metres) {
    s.player.position.x += metres;
    s.player.position.y =
        static_cast<float>(world::surfaceHeight(s.world.terrain(), static_cast<int>(s.player.position.x),
                                                static_cast<int>(s.player.position.z)) +
                           1);
    s.previousPlayer = s.player;
}

// Off-screen contexts keep one frame in flight: submit() returns once the frame before is drawn, not
// its own (docs/ENGINE.md, "One frame in flight"). Frames handed on that way, each meshing and uploading
// new chunks and the HUD's vertices while the one before is still being drawn, must end at the picture
// that drawing and finishing each frame in turn ends at.
TEST_F(RenderTest, FramesInFlightEndAtTheFinishedPicture) {
    const auto walk = [&](bool inFlight) {
        game::GameState s(game::GameDef{});
        render::SceneRenderer r(render::dataDir());
        std::vector<render::Image> pictures;
        for (const float metres : {0.0f, 40.0f, 40.0f, 40.0f}) { // new chunks in view at every step
            standEastOfSpawn(s, metres);
            render::SceneSettings settings;
            settings.viewRadius = 4;
            settings.meshBudgetSeconds = 0.0;
            r.render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
            imgui->beginFrame({kW, kH}, 1.0f / 60.0f);
            ui::drawHud(s, r.atlas(), {});
            imgui->endFrame();
            if (inFlight && pictures.size() < 3) {
                context->submit();
                pictures.emplace_back();
            } else {
                context->present();
                pictures.push_back(render::readFramebuffer(kW, kH));
            }
        }
        return pictures;
    };
    const std::vector<render::Image> finished = walk(false);
    for (std::size_t i = 1; i < finished.size(); ++i) {
        ASSERT_FALSE(finished[i].rgba == finished[i - 1].rgba) << "precondition: step " << i << " changes the picture";
    }
    const render::Image last = walk(true).back();
    EXPECT_TRUE(last.rgba == finished.back().rgba)
        << testing_support::compareImages(last, finished.back()).badPixelShare * 100.0 << "% of pixels differ";
}

// A renderer keeps the meshes one chunk beyond its radius (walking to and fro over a border then meshes
// nothing twice) but draws only the chunks of its radius: after a larger radius it draws what a renderer
// that never had one draws.
TEST_F(RenderTest, ASmallerRadiusDrawsWhatAFreshRendererDraws) {
    game::GameState s(game::GameDef{});
    standEastOfSpawn(s, 70.0f); // where kept chunks beyond radius 4 are in view
    const auto frame = [&](render::SceneRenderer& r, int radius) {
        render::SceneSettings settings;
        settings.viewRadius = radius;
        settings.meshBudgetSeconds = 0.0;
        r.render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
        context->present();
        return render::readFramebuffer(kW, kH);
    };
    render::SceneRenderer kept(render::dataDir()), fresh(render::dataDir());
    const render::Image wide = frame(kept, 6);
    const render::Image narrow = frame(kept, 4);
    EXPECT_FALSE(wide.rgba == narrow.rgba) << "precondition: the radius shows in the picture";
    const render::Image never = frame(fresh, 4);
    EXPECT_TRUE(narrow.rgba == never.rgba)
        << testing_support::compareImages(narrow, never).badPixelShare * 100.0 << "% of pixels differ";
}

// Once everything in range is meshed, update() stops looking at each chunk until the camera changes
// chunk, the radius or the level of detail changes or the world is edited (docs/ENGINE.md). After each
// of those a renderer that had settled must show what a fresh one shows.
TEST_F(RenderTest, SettledMeshesFollowMovesRadiusAndEdits) {
    game::GameState s(game::GameDef{});
    render::SceneRenderer kept(render::dataDir());
    const auto frame = [&](render::SceneRenderer& r, int radius, bool lod) {
        render::SceneSettings settings;
        settings.viewRadius = radius;
        settings.levelOfDetail = lod;
        settings.meshBudgetSeconds = 0.0;
        r.render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
        context->present();
        return render::readFramebuffer(kW, kH);
    };
    const auto settle = [&](int radius, bool lod) {
        frame(kept, radius, lod);
        render::Image image = frame(kept, radius, lod);
        EXPECT_TRUE(kept.stats().chunks.settled) << "precondition: a second frame with nothing new is settled";
        return image;
    };
    // A changed view is never taken for the settled one, and then shows exactly a fresh renderer's picture.
    const auto expectFresh = [&](int radius, bool lod, const char* change) {
        render::Image image = frame(kept, radius, lod);
        EXPECT_FALSE(kept.stats().chunks.settled) << change;
        EXPECT_EQ(kept.stats().chunks.pending, 0) << change;
        render::SceneRenderer fresh(render::dataDir());
        EXPECT_TRUE(image.rgba == frame(fresh, radius, lod).rgba) << change;
        return image;
    };
    settle(6, true);
    standEastOfSpawn(s, 70.0f); // two chunks on
    expectFresh(6, true, "moved two chunks");
    settle(6, true);
    expectFresh(4, true, "smaller radius");
    settle(4, true);
    expectFresh(6, true, "larger radius");
    settle(6, true);
    expectFresh(6, false, "level of detail off");
    const render::Image before = settle(6, false);
    const glm::ivec3 ahead = glm::ivec3(glm::floor(s.player.position)) + glm::ivec3(0, 0, -5);
    for (int y = 0; y < 3; ++y) s.world.set(ahead + glm::ivec3(0, y, 0), world::BlockType::Brick);
    const render::Image edited = expectFresh(6, false, "three bricks placed");
    EXPECT_FALSE(edited.rgba == before.rgba) << "precondition: the bricks are in view";

    // Streaming as the game does (2 ms of meshing a frame, the worker finishing the rest): an edit and the
    // level of detail switched back on (every chunk beyond 4 meshed anew) take frames, and the renderer
    // settles only once every result is in, then showing the fresh picture.
    s.world.set(ahead + glm::ivec3(2, 0, 0), world::BlockType::Brick);
    const auto streamed = [&] {
        render::SceneSettings settings;
        settings.viewRadius = 6;
        settings.meshBudgetSeconds = 0.002;
        kept.render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
        context->present();
        return render::readFramebuffer(kW, kH);
    };
    render::Image last = streamed();
    ASSERT_GT(kept.stats().chunks.pending, 0) << "precondition: one frame does not mesh everything";
    int frames = 1;
    while (frames < 1000 && !kept.stats().chunks.settled) {
        last = streamed();
        ++frames;
    }
    ASSERT_TRUE(kept.stats().chunks.settled) << "streaming never settled";
    render::SceneRenderer fresh(render::dataDir());
    EXPECT_TRUE(last.rgba == frame(fresh, 6, true).rgba) << "settled after streaming, " << frames << " frames";

    // An edit in the chunks around the camera's shows in the frame it is made, streaming as the game
    // does: those chunks are meshed again on this thread, not left to the worker for a later frame
    // (where the worker took it first, now and then), and the blocks around the camera stay occluders.
    // Eight bricks on top of the three, one a frame, then the block under the camera's feet broken.
    const auto expectMeshedHere = [&](const std::string& edit) {
        EXPECT_EQ(kept.stats().chunks.queued, 0) << edit << ": handed to the worker";
        EXPECT_EQ(kept.stats().chunks.pending, 0) << edit << ": waits for the worker";
        EXPECT_GT(kept.stats().chunks.nearPixels, 0) << edit << ": the blocks around the camera stood aside";
    };
    render::Image edit;
    for (int y = 3; y < 11; ++y) {
        s.world.set(ahead + glm::ivec3(0, y, 0), world::BlockType::Brick);
        edit = streamed();
        expectMeshedHere("brick " + std::to_string(y));
    }
    EXPECT_FALSE(edit.rgba == last.rgba) << "precondition: the bricks are in view";
    const glm::ivec3 underfoot = glm::ivec3(glm::floor(s.player.position)) - glm::ivec3(0, 1, 0);
    ASSERT_TRUE(world::isSolid(s.world.get(underfoot))) << "precondition: the player stands on a block";
    s.world.set(underfoot, world::BlockType::Air);
    edit = streamed();
    expectMeshedHere("the block underfoot broken");
    render::SceneRenderer afterEdit(render::dataDir());
    EXPECT_TRUE(edit.rgba == frame(afterEdit, 6, true).rgba) << "the frame of the edit";
}

// Occlusion culling leaves out only what cannot be seen: the same pixels with it and without, in the
// spawn view turned to the four quarters (and one of them as a tile of a larger frame), a view over
// the hills, a room dug deep underground (where the surface is hidden) and a camera inside the rock
// (where the occlusion buffer must stand aside: no ray from there crosses a face drawn in front of
// anything). Both parts are checked: the walk through chunk faces and the occlusion buffer of solid
// columns (docs/ENGINE.md, "Occluders"), whole chunks, and the hidden columns and quads of chunks that
// are drawn.
TEST_F(RenderTest, OcclusionCullingKeepsEveryPixel) {
    game::GameState demo(game::GameDef{});
    game::GameState overview = overviewState();
    game::GameState cave(game::GameDef{});
    const glm::ivec3 room(8, 20, 8);
    for (int y = 0; y < 4; ++y)
        for (int z = -3; z <= 3; ++z)
            for (int x = -3; x <= 3; ++x) cave.world.set(room + glm::ivec3(x, y, z), world::BlockType::Air);
    cave.player.position = glm::vec3(room) + glm::vec3(0.5f, 0.0f, 0.5f);
    cave.player.pitch = 10.0f;
    cave.previousPlayer = cave.player;
    game::GameState rock(game::GameDef{});
    rock.player.position = glm::vec3(room) + glm::vec3(20.5f, 0.0f, 0.5f); // eye height inside the rock
    rock.player.pitch = 5.0f;
    rock.previousPlayer = rock.player;
    ASSERT_TRUE(world::isSolid(rock.world.get(glm::ivec3(glm::floor(render::interpolatedCamera(rock, 1.0f).eye)))))
        << "precondition: the camera is inside the rock";
    // A wall of brick three blocks in front of the spawn camera (yaw 0 looks to -z), with a window of
    // one block at eye height: the blocks around the camera cover most of the view, not the window.
    game::GameState wall(game::GameDef{});
    wall.player.yaw = wall.previousPlayer.yaw = 0.0f;
    const glm::ivec3 eye(glm::floor(render::interpolatedCamera(wall, 1.0f).eye));
    for (int y = -6; y <= 6; ++y)
        for (int x = -8; x <= 8; ++x)
            if (x != 0 || y != 0) wall.world.set(eye + glm::ivec3(x, y, -3), world::BlockType::Brick);
    // Flat ground, where one quad covers each chunk's grass, and a wall hiding the left half of the view:
    // the quads of columns the wall hides reach into columns beside it, so they must still be drawn.
    game::GameDef flatDef;
    flatDef.terrain = world::TerrainDef{1, world::TerrainKind::Flat};
    game::GameState halfWall(flatDef);
    halfWall.player.position = glm::vec3(0.5f, static_cast<float>(world::kFlatSurface + 1), 0.5f);
    halfWall.player.yaw = halfWall.previousPlayer.yaw = 0.0f;
    halfWall.player.pitch = -10.0f;
    halfWall.previousPlayer = halfWall.player;
    for (int y = 1; y <= 12; ++y)
        for (int x = -24; x <= 0; ++x)
            halfWall.world.set(glm::ivec3(x, world::kFlatSurface + y, -4), world::BlockType::Brick);
    glm::ivec2 tileOf{0, 0}, tileAt{0, 0}; // a tile of a larger frame (--screenshot-scale), when set
    const auto drawCulled = [&](const game::GameState& s, bool culling) {
        render::SceneSettings settings;
        settings.frame = tileOf;
        settings.tileOrigin = tileAt;
        settings.viewRadius = 8;
        settings.occlusionCulling = culling;
        settings.meshBudgetSeconds = 0.0;
        scene->render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
        context->present();
        return render::readFramebuffer(kW, kH);
    };
    int walkHidSomewhere = 0, occludedSomewhere = 0, columnsSomewhere = 0, quadsSomewhere = 0, lastDrawn = 0,
        spawnDrawn = 0;
    const auto check = [&](const game::GameState& s, const char* name) {
        const render::Image all = drawCulled(s, false);
        const int drawnAll = scene->stats().chunks.drawn;
        const render::Image culled = drawCulled(s, true);
        const render::ChunkStats& c = scene->stats().chunks;
        std::printf("%s: %d chunks drawn without culling, %d with: %d hidden, %d of them behind %d occluders (%d "
                    "pixels of near blocks); %d columns and %d more quads of the chunks drawn hidden\n",
                    name, drawnAll, c.drawn, c.hidden, c.occluded, c.occluders, c.nearPixels, c.hiddenColumns,
                    c.hiddenQuads);
        lastDrawn = c.drawn;
        EXPECT_EQ(c.drawn + c.hidden, drawnAll) << name;
        walkHidSomewhere += c.hidden - c.occluded;
        occludedSomewhere += c.occluded;
        columnsSomewhere += c.hiddenColumns;
        quadsSomewhere += c.hiddenQuads;
        EXPECT_TRUE(culled.rgba == all.rgba)
            << name << ": " << testing_support::compareImages(culled, all).badPixelShare * 100.0
            << "% of pixels differ";
    };
    for (const float yaw : {0.0f, 90.0f, 180.0f, 270.0f}) {
        demo.player.yaw = demo.previousPlayer.yaw = yaw;
        check(demo, ("spawn view, yaw " + std::to_string(static_cast<int>(yaw))).c_str());
        if (yaw == 0.0f) spawnDrawn = lastDrawn;
    }
    tileOf = {2 * kW, 2 * kH}; // the lower right quarter of a frame twice the size
    tileAt = {kW, kH};
    check(demo, "spawn view, yaw 270, a tile");
    tileOf = tileAt = {0, 0};
    check(overview, "overview");
    check(cave, "cave");
    check(wall, "a wall with a window");
    EXPECT_LT(lastDrawn, spawnDrawn) << "precondition: the wall hides chunks the same view shows without it";
    check(halfWall, "flat ground, a wall on the left");
    EXPECT_GT(scene->stats().chunks.hiddenColumns, 0) << "precondition: the wall hides columns of chunks drawn";
    check(rock, "inside the rock");
    EXPECT_EQ(scene->stats().chunks.occluders, 0) << "the occlusion buffer was used with the camera in rock";
    EXPECT_EQ(scene->stats().chunks.hidden, 0) << "the walk left chunks out with the camera in rock";
    EXPECT_GT(walkHidSomewhere, 0) << "precondition: the views give the walk something to leave out";
    EXPECT_GT(occludedSomewhere, 0) << "precondition: and the occlusion buffer";
    EXPECT_GT(columnsSomewhere, 0) << "precondition: and columns of chunks that are drawn";
    EXPECT_GT(quadsSomewhere, 0) << "precondition: and quads of columns in view";
}

// The scene draws objects with back faces culled, before the terrain: every triangle must be
// counter-clockwise seen from outside, or a sphere would show its inside (or vanish) against the terrain.
TEST_F(RenderTest, ObjectTrianglesFaceOutward) {
    render::EntityRenderer objects(render::dataDir());
    const auto expectOutward = [&](glm::vec3 centre, std::size_t vertices) {
        const auto& v = objects.batched();
        ASSERT_EQ(v.size(), vertices); // precondition: the shape was batched
        for (std::size_t i = 0; i < v.size(); i += 3) {
            const glm::vec3 n = glm::cross(v[i + 1].position - v[i].position, v[i + 2].position - v[i].position);
            const glm::vec3 out = (v[i].position + v[i + 1].position + v[i + 2].position) / 3.0f - centre;
            EXPECT_GT(glm::dot(n, out), 0.0f) << "triangle " << i / 3 << " faces inward";
        }
        objects.flush(glm::mat4(1.0f), render::ChunkLighting{});
    };
    objects.addSphere({1.0f, 2.0f, 3.0f}, 0.5f, {1, 0, 0});
    expectOutward({1.0f, 2.0f, 3.0f}, 8 * 16 * 3); // an octahedron subdivided twice
    objects.addBox({-1.0f, -1.0f, -1.0f}, {2.0f, 1.0f, 0.5f}, {0, 1, 0});
    expectOutward({0.5f, 0.0f, -0.25f}, 6 * 2 * 3);
}

// Greedy quads meet the corners of smaller quads partway along their edges (T-junctions), where the
// rasteriser's rounding used to leave gaps a fraction of a pixel wide: looking down at the hills, a few
// pixels a frame showed the sky through the ground (258 in 40 such views at 1280x720). The chunk vertex
// shader moves each corner outward within its face by a fiftieth of a pixel on the screen (kSealPixels
// in shaders/chunk.vert), so neighbouring quads overlap. Views down from above the hills, straight,
// steep and at a glancing angle from eye height (only the lower half of those counts: it is all
// ground), each drawn as the 16 tiles of a frame four times the size (1280x800), must show no sky.
TEST_F(RenderTest, NoGapBetweenQuadsShowsTheSky) {
    game::GameState s(game::GameDef{});
    s.paused = true; // no outline of a targeted block
    const glm::vec3 fog = render::ChunkLighting{}.fogColor * 255.0f;
    long long skyPixels = 0, drawn = 0;
    for (int view = 0; view < 6; ++view) {
        const int x = 40 * view - 60, z = 30 - 25 * view;
        const bool glancing = view >= 4;
        s.player.position =
            glm::vec3(x + 0.5f, world::surfaceHeight(s.world.terrain(), x, z) + (glancing ? 1.0f : 40.0f), z + 0.5f);
        s.player.yaw = 70.0f * view;
        s.player.pitch = glancing ? -25.0f : view % 2 == 0 ? -89.0f : -60.0f;
        s.previousPlayer = s.player;
        for (int tile = 0; tile < 16; ++tile) {
            if (glancing && tile < 8) continue; // the upper half of the frame may show the sky
            render::SceneSettings settings;
            settings.viewRadius = 6;
            settings.meshBudgetSeconds = 0.0;
            settings.frame = {4 * kW, 4 * kH};
            settings.tileOrigin = {(tile % 4) * kW, (tile / 4) * kH};
            scene->render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
            context->present();
            const render::Image image = render::readFramebuffer(kW, kH);
            drawn += scene->stats().chunks.triangles > 0 ? 1 : 0;
            for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
                if (std::abs(image.rgba[i] - fog.r) <= 3.0f && std::abs(image.rgba[i + 1] - fog.g) <= 3.0f &&
                    std::abs(image.rgba[i + 2] - fog.b) <= 3.0f) {
                    ++skyPixels;
                }
            }
        }
    }
    EXPECT_EQ(drawn, 4 * 16 + 2 * 8) << "precondition: every tile drew terrain";
    EXPECT_EQ(skyPixels, 0) << "pixels of sky seen through the ground";
}

// --frame-stats' overdraw figure: the fragments that pass the depth test. Over flat ground with nothing
// else in the world, a view straight up shades every pixel once with the sky (one triangle over the
// frame, exactly) and a view straight down once with the ground's top faces (the sky fails the depth
// test behind them), but for the slivers where neighbouring quads overlap (below).
TEST_F(RenderTest, FragmentCounterCountsWhatPassesTheDepthTest) {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    game::GameState s(def);
    s.paused = true; // no outline of a targeted block
    s.player.position = glm::vec3(0.5f, 33.0f, 0.5f);
    render::FragmentCounter fragments;
    const auto count = [&](float pitch) {
        s.player.pitch = pitch;
        s.previousPlayer = s.player;
        render::SceneSettings settings;
        settings.meshBudgetSeconds = 0.0;
        fragments.begin();
        scene->render(s, render::interpolatedCamera(s, 1.0f), {kW, kH}, settings);
        fragments.end();
        context->present();
        return fragments.result();
    };
    // Looking down, neighbouring quads of the ground overlap by the seal of shaders/chunk.vert (each
    // corner moved out by a fiftieth of a pixel on the screen), and a pixel whose centre falls in an
    // overlap may pass the depth test twice: about 520 pixels of chunk borders in view times 0.04
    // pixels, some 21 centres, of which the later quad wins about half (9 measured); 50 bounds it. The
    // sky drawn without its depth test, tried on purpose, counted a whole frame more.
    const std::uint64_t down = count(-89.0f);
    EXPECT_GE(down, std::uint64_t{kW} * kH);
    EXPECT_LE(down, std::uint64_t{kW} * kH + 50);
    EXPECT_EQ(count(89.0f), std::uint64_t{kW} * kH);
}

// A hair ball is drawn only when the box of its nodes meets the view: its hair counts, not its centre.
// Without a frustum (lines wider than a pixel, which may reach past the view's edge) every ball is.
TEST_F(RenderTest, HairOutsideTheViewIsLeftOut) {
    render::HairRenderer hair(render::dataDir());
    // The view: x and y in [-1, 1], looking down -z from 0.05 to 100.
    const glm::mat4 viewProjection = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.05f, 100.0f);
    const render::Frustum frustum(viewProjection);
    const game::HairBall ahead(glm::vec3(0.0f, 0.0f, -5.0f)), behind(glm::vec3(0.0f, 0.0f, 5.0f));
    // Beside the view: the sphere (radius 0.3) lies beyond x = 1, its strands (0.45 long, straight out
    // from the surface at the start) reach back to x = 0.75.
    const game::HairBall beside(glm::vec3(1.5f, 0.0f, -5.0f)), farBeside(glm::vec3(2.0f, 0.0f, -5.0f));
    ASSERT_EQ(beside.def().radius, 0.3f);
    ASSERT_EQ(beside.def().hair.strandLength, 0.45f);
    const std::size_t nodes = static_cast<std::size_t>(ahead.solver().activeStrands()) *
                              static_cast<std::size_t>(ahead.solver().nodesPerStrand());
    ASSERT_GT(nodes, 0u) << "precondition: the ball has hair";
    EXPECT_FALSE(hair.add(behind, 1.0f, glm::vec3(0.0f), &frustum));
    EXPECT_FALSE(hair.add(farBeside, 1.0f, glm::vec3(0.0f), &frustum)); // reaches x = 1.25 at most
    EXPECT_TRUE(hair.add(ahead, 1.0f, glm::vec3(0.0f), &frustum));
    EXPECT_TRUE(hair.add(beside, 1.0f, glm::vec3(0.0f), &frustum));
    hair.flush(viewProjection);
    EXPECT_EQ(hair.lastVertexCount(), 2 * nodes);
    EXPECT_TRUE(hair.add(behind, 1.0f, glm::vec3(0.0f), nullptr)); // wide lines: nothing left out
    hair.flush(viewProjection);
    EXPECT_EQ(hair.lastVertexCount(), nodes);
}

// Clicks hit what is drawn (game/object_shapes.h). Over views from all around a swinging set and two
// balls, the object game::targetOf picks is the one an object-ID render of the drawn triangles shows under
// the crosshair. The ID render draws the triangles the scene would draw (EntityRenderer::addShape) in flat
// colours, one per object, on an odd-sized viewport so that the crosshair's ray passes through a pixel's
// centre. Where the two differ, a silhouette must pass within a pixel of the crosshair in both: the ray's
// object is drawn on a neighbouring pixel, and the ray through a neighbouring pixel's centre hits the object
// drawn at the crosshair (the spheres are drawn as polyhedra inside the true sphere, up to 5.7 % of the
// radius short of it).
TEST_F(RenderTest, TheClickTargetIsTheObjectDrawnUnderTheCrosshair) {
    game::GameDef def;
    def.terrain.kind = world::TerrainKind::Flat;
    def.demoObjects = false;
    def.player.reach = 100.0f; // the ID render has no reach: compare every object in view
    game::GameState s(def);
    s.pendulumSets.emplace_back(glm::ivec3(0, 33, 0));
    for (int i = 0; i < 25; ++i) s.pendulumSets[0].tick(1.0 / 60.0); // rods at four different angles
    s.hairBalls.emplace_back(glm::vec3(4.0f, 34.0f, 0.5f), def.ballDef);
    s.hairBalls.emplace_back(glm::vec3(-2.5f, 33.5f, 3.5f), def.ballDef);
    std::vector<game::Shape> setShapes;
    game::appendPendulumSetShapes(s.pendulumSets[0], 1.0, setShapes);
    ASSERT_EQ(setShapes.size(), 3u + 2u * game::kPendulumSlots) << "precondition: post, arms, rods and bobs";

    // An unlit program that writes each vertex's colour as it is: object i + 1 in red, byte for byte.
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "mc_object_id_shaders";
    std::filesystem::create_directories(dir);
    {
        std::ofstream(dir / "id.vert") << "#version 330 core\nlayout(location = 0) in vec3 aPos;\n"
                                          "layout(location = 2) in vec3 aColor;\nuniform mat4 uViewProj;\n"
                                          "flat out vec3 vColor;\nvoid main() { vColor = aColor; "
                                          "gl_Position = uViewProj * vec4(aPos, 1.0); }\n";
        std::ofstream(dir / "id.frag") << "#version 330 core\nflat in vec3 vColor;\nout vec4 fragColor;\n"
                                          "void main() { fragColor = vec4(vColor, 1.0); }\n";
    }
    const render::ShaderProgram idProgram(dir / "id.vert", dir / "id.frag");
    const GLint uViewProj = idProgram.uniform("uViewProj");
    GLuint vao = 0, vbo = 0;
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    using Vertex = render::EntityRenderer::Vertex;
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<const void*>(0));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(2 * sizeof(glm::vec3)));
    render::EntityRenderer tessellator(render::dataDir());

    constexpr int w = kW - 1, h = kH - 1; // odd: the centre is a pixel's centre
    const auto idOf = [&](const game::Target& t) {
        if (t.kind == game::Target::Kind::PendulumSet) return 1 + static_cast<int>(t.index);
        if (t.kind == game::Target::Kind::HairBall) return 1 + static_cast<int>(s.pendulumSets.size() + t.index);
        return 0; // a block or nothing: no object
    };
    std::mt19937 rng(20261127);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), far(1.5f, 7.0f);
    int compared = 0, agreed = 0, grazing = 0;
    std::array<int, 4> hitsOf{}; // views whose ray found nothing, the set, ball 0, ball 1
    for (int view = 0; view < 600; ++view) {
        // Aim near a random shape: a set part (rods and bobs included) half the time, else a ball, at a point
        // within about the shape's own size of its middle, so that hits, misses and edges all come up.
        glm::vec3 aim;
        if (rng() % 2 == 0) {
            const game::Shape& shape = setShapes[rng() % setShapes.size()];
            const bool sphere = shape.kind == game::Shape::Kind::Sphere;
            aim = (sphere ? shape.a : (shape.a + shape.b) * 0.5f) + glm::vec3(unit(rng), unit(rng), unit(rng)) * 0.2f;
        } else {
            const game::HairBall& ball = s.hairBalls[rng() % s.hairBalls.size()];
            aim = ball.centre() + glm::vec3(unit(rng), unit(rng), unit(rng)) * (1.3f * ball.def().radius);
        }
        glm::vec3 away(unit(rng), std::abs(unit(rng)), unit(rng)); // from above: no ground in between
        if (glm::length(away) < 0.1f) continue;
        const glm::vec3 eye = aim + glm::normalize(away) * far(rng);
        if (eye.y < 33.2f) continue; // above the ground, so no block stands between the eye and an object
        const glm::vec3 dir = glm::normalize(aim - eye);
        if (std::abs(dir.y) > 0.999f) continue; // past the pitch limit
        s.player.position = eye - glm::vec3(0.0f, def.player.eyeHeight, 0.0f);
        s.player.yaw = glm::degrees(std::atan2(dir.x, -dir.z));
        s.player.pitch = glm::degrees(std::asin(dir.y));
        s.previousPlayer = s.player;
        const game::Target target = game::targetOf(s);
        const int rayId = idOf(target);
        ++hitsOf[static_cast<std::size_t>(std::min(rayId, 3))];

        // The ID render, from the eye the ray starts at, looking where it points.
        const glm::vec3 look = game::lookDirection(s.player.yaw, s.player.pitch);
        const glm::mat4 viewProjection =
            glm::perspective(glm::radians(70.0f), static_cast<float>(w) / static_cast<float>(h), 0.05f, 200.0f) *
            glm::lookAt(glm::vec3(0.0f), look, glm::vec3(0.0f, 1.0f, 0.0f));
        std::vector<Vertex> vertices;
        const auto addObject = [&](const game::Shape& shape, int id) {
            tessellator.addShape(shape, eye);
            for (Vertex v : tessellator.batched()) {
                v.color = glm::vec3(static_cast<float>(id) / 255.0f, 0.0f, 0.0f);
                vertices.push_back(v);
            }
            tessellator.flush(viewProjection, render::ChunkLighting{}); // draws nothing: the colour pass below wins
        };
        for (const game::Shape& shape : setShapes) addObject(shape, 1);
        for (std::size_t b = 0; b < s.hairBalls.size(); ++b)
            addObject(game::hairBallShape(s.hairBalls[b], 1.0f), 2 + static_cast<int>(b));
        glViewport(0, 0, w, h);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_BLEND);
        idProgram.use();
        glUniformMatrix4fv(uViewProj, 1, GL_FALSE, &viewProjection[0][0]);
        render::streamAndDraw(vao, vbo, vertices, GL_TRIANGLES);
        std::vector<unsigned char> block(3 * 3 * 4);
        glReadPixels(w / 2 - 1, h / 2 - 1, 3, 3, GL_RGBA, GL_UNSIGNED_BYTE, block.data());
        const auto drawnAt = [&](int dx, int dy) { return static_cast<int>(block[((dy + 1) * 3 + (dx + 1)) * 4]); };
        // The ray through the centre of the pixel dx, dy from the crosshair's, as targetOf would cast it.
        const glm::mat4 unproject = glm::inverse(viewProjection);
        const auto rayAt = [&](int dx, int dy) {
            const glm::vec4 p =
                unproject * glm::vec4(2.0f * static_cast<float>(dx) / static_cast<float>(w),
                                      2.0f * static_cast<float>(dy) / static_cast<float>(h), 1.0f, 1.0f);
            const glm::vec3 d = glm::normalize(glm::vec3(p) / p.w);
            const game::Player held = s.player;
            s.player.yaw = glm::degrees(std::atan2(d.x, -d.z));
            s.player.pitch = glm::degrees(std::asin(d.y));
            const int id = idOf(game::targetOf(s));
            s.player = held;
            return id;
        };
        const int drawnId = drawnAt(0, 0);
        ++compared;
        if (drawnId == rayId) {
            ++agreed;
            continue;
        }
        // A silhouette runs between the crosshair and a neighbouring pixel in both: the ray's object is drawn
        // next to the centre, and the object drawn at the centre is hit by a neighbouring pixel's ray.
        bool drawnNextTo = false, hitNextTo = false;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                drawnNextTo = drawnNextTo || drawnAt(dx, dy) == rayId;
                hitNextTo = hitNextTo || ((dx != 0 || dy != 0) && rayAt(dx, dy) == drawnId);
            }
        }
        EXPECT_TRUE(drawnNextTo && hitNextTo)
            << "view " << view << ": the click acts on object " << rayId << " but object " << drawnId
            << " is drawn under the crosshair, away from any edge (eye " << eye.x << " " << eye.y << " " << eye.z
            << ", yaw " << s.player.yaw << ", pitch " << s.player.pitch << ")";
        ++grazing;
    }
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &vbo);
    glViewport(0, 0, kW, kH);
    std::printf("%d views: %d agree at the crosshair, %d graze a silhouette; the ray found nothing %d, the set %d, "
                "the balls %d and %d times\n",
                compared, agreed, grazing, hitsOf[0], hitsOf[1], hitsOf[2], hitsOf[3]);
    EXPECT_GT(compared, 500) << "precondition: most views were usable";
    for (const int n : hitsOf) EXPECT_GT(n, 30) << "precondition: every object and the empty sky under the ray";
    EXPECT_LT(grazing, compared / 20) << "grazing views are rare: more means the shapes differ";
}

TEST_F(RenderTest, SkyAboveHorizonGroundBelow) {
    game::GameState s = flatScene();
    s.player.pitch = 0.0f;
    s.previousPlayer = s.player;
    const auto img = draw(s, false);
    const auto sky = pixel(img, kW / 2, 5);
    const auto ground = pixel(img, kW / 2, kH - 5);
    EXPECT_GT(sky.b, sky.r);
    EXPECT_GT(ground.g, ground.b); // grass
}

} // namespace
