#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include <glm/common.hpp>

#include "render/gl.h"
#include "render/gl_loader.h"
#include "ui/ui.h"

#include "input/keys.h"
#include "render/daylight.h"
#include "ui/hotbar_layout.h"
#include "ui/item_icon.h"
#include "world/block.h"
#include "world/column_light.h"

namespace ui {

ImGuiLayer::ImGuiLayer(GLFWwindow* window) : m_glfw(window != nullptr) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini littering the working directory
    // Keyboard and gamepad navigation need a platform backend to map keys; headless frames have none.
    if (m_glfw) io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard | ImGuiConfigFlags_NavEnableGamepad;
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 4.0f;
    if (m_glfw) ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
}

ImGuiLayer::~ImGuiLayer() {
    ImGui_ImplOpenGL3_Shutdown();
    if (m_glfw) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void ImGuiLayer::beginFrame(glm::ivec2 displaySize, float deltaSeconds, float framebufferScale) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGuiIO& io = ImGui::GetIO();
    if (m_glfw) {
        ImGui_ImplGlfw_NewFrame();
    } else {
        io.DisplaySize = ImVec2(static_cast<float>(displaySize.x), static_cast<float>(displaySize.y));
        io.DeltaTime = deltaSeconds > 0.0f ? deltaSeconds : 1.0f / 60.0f;
        io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
    }
    if (framebufferScale != 1.0f) io.DisplayFramebufferScale = ImVec2(framebufferScale, framebufferScale);
    ImGui::NewFrame();
    // This frame saw the tapped keys pressed; the next one sees them released (unless pressed again by then).
    for (const int key : m_heldForOneFrame) io.KeysDown[key] = false;
    if (!m_heldForOneFrame.empty()) updateModifiers(); // from the keys now down
    m_heldForOneFrame.clear();
    m_pressedSinceFrame.clear();
}

void ImGuiLayer::noteKey(int key, bool down) {
    ImGuiIO& io = ImGui::GetIO();
    if (!m_glfw || key < 0 || key >= static_cast<int>(IM_ARRAYSIZE(io.KeysDown))) return;
    if (down) {
        m_pressedSinceFrame.push_back(key);
    } else if (std::find(m_pressedSinceFrame.begin(), m_pressedSinceFrame.end(), key) != m_pressedSinceFrame.end()) {
        io.KeysDown[key] = true; // the backend's callback has just set it false
        m_heldForOneFrame.push_back(key);
    }
    updateModifiers();
}

// The modifiers as the backend derives them from the keys held, so that a Ctrl tapped around a click (held
// for ImGui by noteKey) counts for the click.
void ImGuiLayer::updateModifiers() {
    ImGuiIO& io = ImGui::GetIO();
    const auto either = [&](int a, int b) { return io.KeysDown[a] || io.KeysDown[b]; };
    namespace k = input::key;
    io.KeyCtrl = either(k::LeftControl, k::RightControl);
    io.KeyShift = either(k::LeftShift, k::RightShift);
    io.KeyAlt = either(k::LeftAlt, k::RightAlt);
    io.KeySuper = either(k::LeftSuper, k::RightSuper);
}

bool ImGuiLayer::ownsEscape() const {
    return ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel) ||
           ImGui::GetIO().WantTextInput;
}

void ImGuiLayer::finishLayout() { ImGui::Render(); }

namespace {

// Draws the UI and counts its draw calls (one per command) unless they went through the counting
// forwarders already (the backend uses glDrawElementsBaseVertex on GL 3.2+, which they do not see).
void renderCounted(ImDrawData* d) {
    const std::uint64_t before = render::drawCallsIssued();
    ImGui_ImplOpenGL3_RenderDrawData(d);
    if (render::drawCallsIssued() != before) return;
    std::uint64_t commands = 0;
    for (int i = 0; i < d->CmdListsCount; ++i) {
        for (const ImDrawCmd& cmd : d->CmdLists[i]->CmdBuffer) commands += cmd.UserCallback == nullptr ? 1u : 0u;
    }
    render::countDrawCalls(commands);
}

} // namespace

void ImGuiLayer::drawTile(glm::ivec2 tileOrigin, glm::ivec2 tileSize) {
    ImDrawData* d = ImGui::GetDrawData();
    if (!d) return;
    const ImVec2 pos = d->DisplayPos, size = d->DisplaySize;
    const ImVec2 scale = d->FramebufferScale;
    // The backend projects DisplayPos..DisplayPos+DisplaySize onto the viewport and clips relative to
    // DisplayPos: shifting them to the tile draws exactly the tile's part.
    d->DisplayPos =
        ImVec2(pos.x + static_cast<float>(tileOrigin.x) / scale.x, pos.y + static_cast<float>(tileOrigin.y) / scale.y);
    d->DisplaySize = ImVec2(static_cast<float>(tileSize.x) / scale.x, static_cast<float>(tileSize.y) / scale.y);
    renderCounted(d);
    d->DisplayPos = pos;
    d->DisplaySize = size;
}

void ImGuiLayer::endFrame() {
    ImGui::Render();
    if (ImDrawData* d = ImGui::GetDrawData()) renderCounted(d);
}

void ImGuiLayer::discardFrame() { ImGui::EndFrame(); }

bool ImGuiLayer::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

namespace {
// The hotbar's icons are lit as the things they stand for would be where the player's eyes are (the light's
// colour, render::localTint), though never below kLeastIconLight, so that the hotbar stays readable in the dark.
constexpr float kLeastIconLight = 0.35f;
glm::vec3 iconLight(const game::GameState& state) {
    const world::LocalLight l = world::lightAt(state.world, glm::ivec3(glm::floor(game::eyePosition(state.player))));
    return glm::max(render::localTint(render::daylightAt(state.day.hours), l.sun, {l.red, l.green, l.blue}),
                    glm::vec3(kLeastIconLight));
}
} // namespace

void drawHud(const game::GameState& state, const render::BlockAtlas& atlas, const HudMessage& message) {
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    const ImVec2 c(size.x * 0.5f, size.y * 0.5f);

    if (!state.paused) {
        // Crosshair: a dark outline under a light cross reads on sky and on snow alike.
        const float r = 9.0f;
        for (const auto& [col, w] :
             {std::pair{IM_COL32(0, 0, 0, 160), 4.0f}, std::pair{IM_COL32(255, 255, 255, 230), 2.0f}}) {
            dl->AddLine(ImVec2(c.x - r, c.y), ImVec2(c.x + r, c.y), col, w);
            dl->AddLine(ImVec2(c.x, c.y - r), ImVec2(c.x, c.y + r), col, w);
        }
    }

    // Hotbar along the bottom edge, icons are each block's side tile; it fits any frame (ui/hotbar_layout.h).
    const HotbarLayout bar = hotbarLayout({size.x, size.y});
    const float slot = bar.slot, in = bar.inset;
    const float y0 = bar.corner[0].y;
    const ImTextureID tex = reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(atlas.flatTexture()));
    const game::Player& p = state.player;
    const glm::vec3 light = iconLight(state);
    for (int i = 0; i < game::kHotbarSize; ++i) {
        const glm::vec2 corner = bar.corner[static_cast<std::size_t>(i)];
        const ImVec2 a(corner.x, corner.y), b(a.x + slot, a.y + slot);
        dl->AddRectFilled(a, b, IM_COL32(20, 20, 20, 170), std::min(3.0f, slot * 0.1f));
        const game::Item& item = p.hotbar[static_cast<std::size_t>(i)];
        drawItemIcon(dl, item, a, b, in, tex, light);
        const char digit[2] = {static_cast<char>('1' + i), 0};
        dl->AddText(ImGui::GetFont(), bar.digitSize, ImVec2(a.x + std::min(3.0f, in), a.y + std::min(1.0f, in)),
                    IM_COL32(255, 255, 255, 200), digit);
        if (i == p.selectedSlot) {
            const float o = std::min(2.0f, bar.pad * 0.5f); // the frame stays in the gap, off the neighbours
            dl->AddRect(ImVec2(a.x - o, a.y - o), ImVec2(b.x + o, b.y + o), IM_COL32(255, 255, 255, 255), 4.0f, 0,
                        std::clamp(slot * 0.08f, 1.0f, 3.0f));
        }
    }
    std::string selected(game::itemName(p.selectedItem()));
    std::replace(selected.begin(), selected.end(), '_', ' ');
    const ImVec2 ts = ImGui::CalcTextSize(selected.c_str());
    dl->AddText(ImVec2(c.x - ts.x * 0.5f, y0 - ts.y - 6.0f), IM_COL32(255, 255, 255, 230), selected.c_str());

    if (p.flying) dl->AddText(ImVec2(12.0f, size.y - 28.0f), IM_COL32(255, 255, 160, 230), "flying");
    if (message.secondsLeft > 0.0 && !message.text.empty()) {
        const ImVec2 ms = ImGui::CalcTextSize(message.text.c_str());
        const ImVec2 a(c.x - ms.x * 0.5f - 8.0f, 16.0f);
        dl->AddRectFilled(a, ImVec2(a.x + ms.x + 16.0f, a.y + ms.y + 10.0f), IM_COL32(0, 0, 0, 170), 4.0f);
        dl->AddText(ImVec2(a.x + 8.0f, a.y + 5.0f), IM_COL32(255, 255, 255, 255), message.text.c_str());
    }
}

} // namespace ui
