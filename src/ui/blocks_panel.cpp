// The block picker, a page of the pause menu: every block and the two lab objects, each a button with the icon
// the hotbar draws (ui/item_icon.h); choosing one puts it into the selected hotbar slot (Session::queueHotbar, recorded
// as a script's `hotbar SLOT ITEM` line). Mouse, keyboard and gamepad reach it alike (ImGui's navigation).
#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "game/item.h"
#include "ui/item_icon.h"
#include "ui/panel_fit.h"
#include "ui/ui.h"

namespace ui {

namespace {

// A name as the hotbar writes it: "red lamp" for red_lamp.
std::string spokenName(const game::Item& item) {
    std::string name(game::itemName(item));
    std::replace(name.begin(), name.end(), '_', ' ');
    return name;
}

} // namespace

void showBlocksPanel(BlocksPanel& panel, const game::Player& player, const render::BlockAtlas& atlas, bool* open) {
    panel.chosen.reset();
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.45f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    fitNextWindowToDisplay();
    if (ImGui::Begin("Blocks", open, kPanelFlags | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove)) {
        const int slot = player.selectedSlot;
        ImGui::Text("Slot %d holds %s. Choose what it holds:", slot + 1,
                    spokenName(player.hotbar[static_cast<std::size_t>(slot)]).c_str());
        const auto texture = reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(atlas.flatTexture()));
        const float icon = std::clamp(display.y / 14.0f, 24.0f, 48.0f);
        constexpr int kColumns = 5;
        const std::vector<game::Item> items = game::everyItem();
        if (ImGui::BeginTable("##blocks", kColumns, ImGuiTableFlags_SizingFixedSame)) {
            for (std::size_t i = 0; i < items.size(); ++i) {
                const game::Item& item = items[i];
                ImGui::TableNextColumn();
                ImGui::PushID(static_cast<int>(i));
                const bool held = item == player.hotbar[static_cast<std::size_t>(slot)];
                if (held) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
                // A button the size an image button of the icon would be, the icon drawn on it as in the hotbar.
                const ImGuiStyle& style = ImGui::GetStyle();
                const bool pressed = ImGui::Button(
                    "##item", ImVec2(icon + 2.0f * style.FramePadding.x, icon + 2.0f * style.FramePadding.y));
                const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
                drawItemIcon(
                    ImGui::GetWindowDrawList(), item, ImVec2(lo.x + style.FramePadding.x, lo.y + style.FramePadding.y),
                    ImVec2(hi.x - style.FramePadding.x, hi.y - style.FramePadding.y), 0.0f, texture, glm::vec3(1.0f));
                if (held) ImGui::PopStyleColor();
                if (pressed) panel.chosen = item;
                if (ImGui::IsItemHovered() || ImGui::IsItemFocused()) panel.hovered = spokenName(item);
                ImGui::PopID();
            }
            ImGui::EndTable();
        }
        ImGui::TextUnformatted(panel.hovered.empty() ? " " : panel.hovered.c_str());
    }
    ImGui::End();
}

} // namespace ui
