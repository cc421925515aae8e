#include "ui/item_icon.h"

#include <algorithm>
#include <cmath>

#include "render/texture.h"
#include "world/block.h"

namespace ui {

namespace {

ImU32 lit(int r, int g, int b, glm::vec3 light) {
    const auto c = [](int v, float f) {
        return static_cast<int>(std::lround(std::min(1.0f, f) * static_cast<float>(v)));
    };
    return IM_COL32(c(r, light.r), c(g, light.g), c(b, light.b), 255);
}

// A pendulum set: a post, a crossbar and two bobs in their colours.
void drawPendulumIcon(ImDrawList* dl, ImVec2 a, ImVec2 b, glm::vec3 light) {
    const float w = b.x - a.x, h = b.y - a.y;
    const auto at = [&](float fx, float fy) { return ImVec2(a.x + fx * w, a.y + fy * h); };
    dl->AddRectFilled(at(0.46f, 0.15f), at(0.54f, 0.9f), lit(150, 110, 70, light));
    dl->AddRectFilled(at(0.15f, 0.15f), at(0.85f, 0.22f), lit(150, 110, 70, light));
    dl->AddLine(at(0.2f, 0.2f), at(0.12f, 0.62f), lit(230, 230, 230, light), 1.5f);
    dl->AddLine(at(0.8f, 0.2f), at(0.92f, 0.6f), lit(230, 230, 230, light), 1.5f);
    dl->AddCircleFilled(at(0.12f, 0.66f), w * 0.08f, lit(235, 235, 235, light));
    dl->AddCircleFilled(at(0.92f, 0.64f), w * 0.08f, lit(230, 80, 60, light));
}

// A hair ball: a ball with strands fanning out.
void drawHairBallIcon(ImDrawList* dl, ImVec2 a, ImVec2 b, glm::vec3 light) {
    const ImVec2 c((a.x + b.x) * 0.5f, (a.y + b.y) * 0.5f - 2.0f);
    const float r = (b.x - a.x) * 0.18f;
    for (int i = 0; i < 14; ++i) {
        const float ang = 3.14159265f * (0.1f + 0.8f * static_cast<float>(i) / 13.0f);
        const ImVec2 tip(c.x + std::cos(ang) * r * 2.6f, c.y + std::sin(ang) * r * 2.4f);
        dl->AddLine(c, tip, lit(230, 150, 70, light), 1.2f);
    }
    dl->AddCircleFilled(c, r, lit(200, 120, 60, light));
}

} // namespace

void drawItemIcon(ImDrawList* dl, const game::Item& item, ImVec2 a, ImVec2 b, float inset, ImTextureID atlas,
                  glm::vec3 light) {
    if (item.kind == game::ItemKind::Block) {
        const int tile = world::blockInfo(item.block).tileSide;
        const float u = static_cast<float>(tile % render::kAtlasTilesPerRow) / render::kAtlasTilesPerRow;
        const int row = tile / render::kAtlasTilesPerRow; // whole rows: integer division on purpose
        const float v = static_cast<float>(row) / render::kAtlasTilesPerRow;
        const float t = 1.0f / render::kAtlasTilesPerRow;
        dl->AddImage(atlas, ImVec2(a.x + inset, a.y + inset), ImVec2(b.x - inset, b.y - inset), ImVec2(u, v),
                     ImVec2(u + t, v + t), lit(255, 255, 255, light));
    } else if (item.kind == game::ItemKind::PendulumSet) {
        drawPendulumIcon(dl, a, b, light);
    } else {
        drawHairBallIcon(dl, a, b, light);
    }
}

} // namespace ui
