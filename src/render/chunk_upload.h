// The GPU side of chunk meshes: each chunk's vertex buffer, the shared index buffer, the frame's index
// buffer of partly hidden chunks, the chunk shader and the draw calls. Separate from streaming and
// culling, which decide what to mesh and what to draw, so that everything that touches GL for chunks,
// and a change to how vertices are laid out or drawn, lands in this one file. It decides nothing: it
// uploads what it is given and draws the ranges it is told.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <unordered_map>
#include <vector>

#include "render/chunk_lod.h"
#include "render/gl.h"
#include "render/shader.h"
#include "world/chunk.h"
#include "world/chunk_vertex.h"
#include "world/culling_data.h"
#include "world/plane_order.h"

namespace render {

// The light of the time of day (render/daylight.h) as the world's shaders take it; the defaults are noon's.
struct ChunkLighting {
    glm::vec3 sunDirection{0.35f, 0.85f, 0.4f}; // towards the light faces are shaded by (the sun, or the moon)
    glm::vec3 sunColour{1.0f};                  // that light's strength by colour
    glm::vec3 skyColour{1.0f};                  // the sky's light on every face
    glm::vec3 fogColor{0.62f, 0.76f, 0.93f};
    float fogStart = 100.0f, fogEnd = 128.0f; // blocks
};

// One chunk's mesh. ChunkUpload fills the GL objects, the order and the per-quad boxes; the streaming
// records what it was made from (revision, detail, culling); the culling marks seenInFrame.
struct GpuMesh {
    GLuint vao = 0, vbo = 0;
    int quads = 0;
    world::PlaneOrder order; // where each face direction's quads start, plane by plane
    std::uint64_t revision = 0;
    ChunkDetail detail;
    world::CullingData culling; // of the chunk this mesh was made from
    // Where the mesh's quads lie, per column of SolidColumns::kCell x kCell blocks: between heights
    // low and high (chunk-local), none where low > high. The occlusion test's boxes: far tighter than
    // the chunk's, whose top a single tree sets.
    struct Span {
        std::uint8_t low = 0xFF, high = 0;
    };
    std::array<Span, world::SolidColumns::kCells * world::SolidColumns::kCells> spans{};
    // Per quad, in drawing order: bit SolidColumns::index(cx, cz) set for each column it reaches into.
    std::vector<std::uint16_t> quadColumns;
    // Per quad, in drawing order: its box, chunk-local (a quad is flat: low and high are equal
    // along its normal). The occlusion test's boxes for the quads of columns that are in view.
    struct QuadBox {
        std::uint8_t low[3], high[3];
    };
    std::vector<QuadBox> quadBoxes;
    // markVisible's frame number when it reached this chunk (mutable: the walk's mark, not the mesh's
    // content, set through the const meshes the culling reads).
    mutable std::uint64_t seenInFrame = 0;
};

class ChunkUpload {
public:
    using Meshes = std::unordered_map<world::ChunkCoord, GpuMesh, world::ChunkCoordHash>;

    explicit ChunkUpload(const std::filesystem::path& dataDir); // compiles the chunk shader
    ~ChunkUpload();                                             // releases every mesh
    ChunkUpload(const ChunkUpload&) = delete;
    ChunkUpload& operator=(const ChunkUpload&) = delete;

    // The meshes, by chunk. Only entry() adds one (empty until upload()); only releaseAll and
    // releaseIf remove them, so that every GL object is deleted with its mesh.
    const Meshes& meshes() const { return m_meshes; }
    GpuMesh& entry(world::ChunkCoord c) { return m_meshes[c]; }
    // Changes whenever a mesh is uploaded or released: lists of meshes built from meshes() are stale.
    std::uint64_t version() const { return m_version; }
    // Sorts cpu's quads by face direction and plane into the mesh's buffer (releasing it if empty) and
    // records each quad's columns and box.
    void upload(GpuMesh& mesh, const world::ChunkMesh& cpu);
    void releaseAll();
    template <class Drop>
    void releaseIf(Drop&& drop) { // drop(coord): whether that chunk's mesh goes
        for (auto it = m_meshes.begin(); it != m_meshes.end();) {
            if (drop(it->first)) {
                release(it->second);
                it = m_meshes.erase(it);
            } else {
                ++it;
            }
        }
    }

    // Drawing, in this order: the shader and its uniforms for the frame; the frame's indices of the
    // chunks with some quads hidden (draw-time culling), if any; then per chunk bindChunk and its draw
    // calls, each returning the triangles it drew; endDraw.
    void useShader(const glm::mat4& viewProjection, glm::ivec2 viewport, GLuint atlasArray, const ChunkLighting&);
    void uploadPartIndices(const std::vector<std::uint32_t>& indices);
    void bindChunk(const GpuMesh& mesh, const glm::vec3& offset);
    long long drawPart(std::size_t first, long long count); // count indices of the part buffer from first
    long long drawQuads(int from, int to);                  // quads [from, to) of the bound chunk, whole
    void endDraw();

private:
    void ensureIndexCapacity(int quads);
    void release(GpuMesh& mesh);

    ShaderProgram m_shader;
    GLint m_uViewProj, m_uOffset, m_uSunDir, m_uSunColour, m_uSkyColour, m_uAtlas, m_uFogColor, m_uFogRange,
        m_uHalfViewport, m_uEmissiveTiles, m_uLampColour;
    GLuint m_indexBuffer = 0;
    // This frame's indices of the chunks with some quads hidden (their other quads, in drawing order) are
    // uploaded to this buffer.
    GLuint m_partIndexBuffer = 0;
    int m_indexQuads = 0;
    Meshes m_meshes;
    std::vector<world::ChunkVertex> m_sorted;
    std::uint64_t m_version = 1;
};

} // namespace render
