#include "render/texture.h"

#include <stb/stb_image.h>

#include <memory>
#include <vector>

#include "render/context.h"

namespace render {

BlockAtlas::BlockAtlas(const std::filesystem::path& png) {
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(png.c_str(), &w, &h, &channels, 4), stbi_image_free);
    if (!pixels) throw RenderError("cannot load texture atlas " + png.string() + ": " + stbi_failure_reason());
    if (w != h || w % kAtlasTilesPerRow != 0) {
        throw RenderError("texture atlas " + png.string() + " must be square with a side divisible by 16, is " +
                          std::to_string(w) + "x" + std::to_string(h));
    }
    const int tile = w / kAtlasTilesPerRow;
    const int layers = kAtlasTilesPerRow * kAtlasTilesPerRow;

    // Re-pack row-major tiles into consecutive layers.
    std::vector<unsigned char> packed(static_cast<std::size_t>(tile) * tile * 4 * layers);
    for (int layer = 0; layer < layers; ++layer) {
        const int tx = (layer % kAtlasTilesPerRow) * tile, ty = (layer / kAtlasTilesPerRow) * tile;
        for (int y = 0; y < tile; ++y) {
            const unsigned char* src = pixels.get() + (static_cast<std::size_t>(ty + y) * w + tx) * 4;
            unsigned char* dst = packed.data() + ((static_cast<std::size_t>(layer) * tile + y) * tile) * 4;
            std::copy(src, src + tile * 4, dst);
        }
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glGenTextures(1, &m_array);
    glBindTexture(GL_TEXTURE_2D_ARRAY, m_array);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, tile, tile, layers, 0, GL_RGBA, GL_UNSIGNED_BYTE, packed.data());
    glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
    // Crisp pixels up close, mipmaps far away (no shimmering on distant hills). One mip level per
    // sample rather than a blend of two: on a CPU rasteriser the blend costs a second texture fetch for
    // every fragment, and with 16-pixel pixel art the level transitions are hard to see.
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);

    glGenTextures(1, &m_flat);
    glBindTexture(GL_TEXTURE_2D, m_flat);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.get());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
}

BlockAtlas::~BlockAtlas() {
    glDeleteTextures(1, &m_array);
    glDeleteTextures(1, &m_flat);
}

} // namespace render
