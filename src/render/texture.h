// The block atlas on the GPU: as a 2D array texture (one layer per 16x16 tile), so tiles repeat across
// merged quads and mipmaps never bleed between neighbours; and as a plain 2D texture for the hotbar.
#pragma once
#include <filesystem>

#include "render/gl.h"

namespace render {

inline constexpr int kAtlasTilesPerRow = 16;

class BlockAtlas {
public:
    explicit BlockAtlas(const std::filesystem::path& png); // throws RenderError naming the file
    ~BlockAtlas();
    BlockAtlas(const BlockAtlas&) = delete;
    BlockAtlas& operator=(const BlockAtlas&) = delete;

    GLuint arrayTexture() const { return m_array; }
    GLuint flatTexture() const { return m_flat; }

private:
    GLuint m_array = 0;
    GLuint m_flat = 0;
};

} // namespace render
