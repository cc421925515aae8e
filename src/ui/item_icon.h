// An item drawn as the hotbar shows it: a block's side tile from the atlas, or the lab objects' drawn icons. The
// hotbar (ui/hud.cpp) and the pause menu's Blocks page (ui/blocks_panel.cpp) both draw with it.
#pragma once
#include <imgui.h>

#include <glm/vec3.hpp>

#include "game/item.h"

namespace ui {

// Draws `item` into the square [a, b] of `dl`, lit by `light` (1 in each channel: as it is): a block's side tile
// (from `atlas`, the block atlas's flat texture) inset by `inset` on every side, an object's icon over the whole.
void drawItemIcon(ImDrawList* dl, const game::Item& item, ImVec2 a, ImVec2 b, float inset, ImTextureID atlas,
                  glm::vec3 light);

} // namespace ui
