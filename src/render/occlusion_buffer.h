// A small software depth buffer for conservative occlusion culling on the CPU (docs/ENGINE.md,
// "Occluders"). Boxes known to be solid are drawn into it; a box is then hidden when every ray through
// its silhouette on the screen meets one of them nearer than the box's nearest point. Nothing here reads GL:
// it is plain geometry over a view-projection matrix, so it can decide, before anything is issued,
// which chunks the frame need not draw.
//
// What a pixel holds is a promise about every ray through every point of its area (not only its
// centre): the ray enters some occluder at a view depth no greater than the value. So an occluder
// counts only at pixels its silhouette covers wholly (inner coverage), with the farthest view depth of
// its corners; and a box is tested against every pixel its silhouette touches, with its nearest
// corner's depth. Both bounds are exact for a box in front of the near plane, because the view depth
// (clip w) is linear in position and so extreme at corners.
#pragma once
#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

namespace render {

// A box of blocks, each solid (opaque) or air, for OcclusionBuffer::addSolidBlocks: bit x % 32 of
// rows[(y * size.z + z) * words() + x / 32] is set where block (x, y, z) of the box is solid. origin is
// where block (0, 0, 0) begins, in the buffer's space (e.g. camera-relative); a block is one unit.
struct SolidGrid {
    glm::ivec3 size{0}; // size.x a multiple of 32
    glm::vec3 origin{0.0f};
    std::vector<std::uint32_t> rows;

    void reset(const glm::ivec3& blocks, const glm::vec3& at); // all air; throws unless blocks.x % 32 == 0
    int words() const { return size.x / 32; }
    std::uint32_t* row(int y, int z) { return rows.data() + (static_cast<std::ptrdiff_t>(y) * size.z + z) * words(); }
    bool solid(int x, int y, int z) const { // false outside the box
        if (x < 0 || y < 0 || z < 0 || x >= size.x || y >= size.y || z >= size.z) return false;
        const int word = (y * size.z + z) * words() + x / 32;
        return (rows[static_cast<std::size_t>(word)] >> (x % 32) & 1u) != 0;
    }
};

class OcclusionBuffer {
public:
    // 160 x 90 pixels: each is 8 x 8 pixels of a 1280 x 720 frame. Any size works (the test is made in
    // normalised device coordinates); coarser pixels cover less of an occluder's rim.
    explicit OcclusionBuffer(int width = 160, int height = 90);

    // Empties the buffer for a frame drawn with viewProjection (a perspective projection; positions
    // passed below are in the same space, e.g. camera-relative).
    void clear(const glm::mat4& viewProjection);
    // Draws a box known to be opaque throughout. Left out (returns false) unless it lies wholly between
    // the near and the far plane (only then is the silhouette the hull of its corners and every ray
    // into it drawn), and where it covers no pixel wholly. The caller must also make sure that every
    // ray from the near plane into the box crosses a drawn opaque surface on the way (the box is solid
    // and the camera and the near plane in air).
    bool addOccluder(const glm::vec3& min, const glm::vec3& max);
    // True when nothing of the box can be seen past the occluders: it lies wholly beyond the near
    // plane and at every pixel its silhouette touches an occluder is nearer than its nearest corner, by
    // a margin that keeps a 24-bit depth buffer with the near plane at 0.05 from ever ordering them the
    // other way (depthMargin). A box beyond the near plane that touches no pixel (off the screen) is
    // hidden too, once any occluder is drawn.
    bool hides(const glm::vec3& min, const glm::vec3& max) const;
    // The same promise as hides, tested more cheaply and less tightly: against every pixel that the
    // screen rectangle around the box's corners touches (it holds the silhouette), not only those the
    // silhouette touches; so it never says hidden where hides would not. A box flat along an axis (a
    // quad) projects four corners, not eight. For many small boxes, such as a mesh's quads.
    bool hidesBounds(const glm::vec3& min, const glm::vec3& max) const;
    // Draws the solid blocks of a grid as occluders, block by block, with no seams between them. The
    // pixels are taken in tiles of 2 x 2: a tile's pixels get view depth w when the section of the
    // tile's pyramid of rays at depth w (the tile widened as addOccluder narrows a silhouette) lies
    // wholly inside solid blocks, so every ray through the tile is inside solid there and entered it
    // no deeper. The tile's centre ray is followed block by block from the eye, out to maxDepth, the
    // far plane or the farthest value of the tile's pixels, whichever is nearest, or out of the grid;
    // at each solid block it crosses, the section at the middle of the crossing is tested. Returns the
    // pixels it lowered (0 for a projection that is not a perspective one). The caller must make sure,
    // as for addOccluder, that the eye and the near plane are in air and that every face between air
    // and a solid block of the grid is drawn.
    int addSolidBlocks(const SolidGrid& grid, float maxDepth);

    // The view depth an occluder is known to be within at pixel (x, y), y up; infinity where none is.
    float depthAt(int x, int y) const {
        return m_depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x)];
    }
    int width() const { return m_width; }
    int height() const { return m_height; }
    int occluders() const { return m_occluders; } // drawn since clear()
    static float depthMargin(float depth);

private:
    struct Projected {
        std::array<glm::vec2, 8> corner; // pixel coordinates, y up
        float nearest, farthest;
    };
    // False unless all eight corners lie inside the near plane (and, with farToo, the far plane).
    bool project(const glm::vec3& min, const glm::vec3& max, bool farToo, Projected& out) const;
    // Whether pixels x0..x1 of row j each hold an occluder nearer than view depth `nearest` by the
    // depth margin: the test both hides and hidesBounds make of every pixel they touch.
    bool rowHides(int j, int x0, int x1, float nearest) const;

    int m_width, m_height;
    glm::mat4 m_viewProjection{1.0f};
    std::vector<float> m_depth;
    int m_occluders = 0;
};

} // namespace render
