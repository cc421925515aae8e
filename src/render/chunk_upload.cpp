// The GPU side of chunk meshes: vertex and index buffers, the chunk shader and the draw calls
// (chunk_upload.h says why this is a unit of its own).
#include "render/chunk_upload.h"

#include "render/daylight.h"

#include <algorithm>

namespace render {

namespace {
// Bit t set when atlas tile t is a face of a block that gives light (world::BlockInfo::emission): the
// chunk shader draws those faces at their own full colour, by day and by night.
std::uint32_t emissiveTiles() {
    static const std::uint32_t mask = [] {
        std::uint32_t m = 0;
        for (int i = 0; i < world::kBlockTypeCount; ++i) {
            const world::BlockInfo& info = world::blockInfo(static_cast<world::BlockType>(i));
            if (!info.emission.any()) continue;
            for (const int tile : {info.tileTop, info.tileSide, info.tileBottom})
                if (tile < 32) m |= 1u << tile;
        }
        return m;
    }();
    return mask;
}
} // namespace

ChunkUpload::ChunkUpload(const std::filesystem::path& dataDir)
    : m_shader(dataDir / "shaders" / "chunk.vert", dataDir / "shaders" / "chunk.frag") {
    m_uViewProj = m_shader.uniform("uViewProj");
    m_uOffset = m_shader.uniform("uOffset");
    m_uSunDir = m_shader.uniform("uSunDir");
    m_uSunColour = m_shader.uniform("uSunColour");
    m_uSkyColour = m_shader.uniform("uSkyColour");
    m_uAtlas = m_shader.uniform("uAtlas");
    m_uFogColor = m_shader.uniform("uFogColor");
    m_uFogRange = m_shader.uniform("uFogRange");
    m_uHalfViewport = m_shader.uniform("uHalfViewport");
    m_uEmissiveTiles = m_shader.uniform("uEmissiveTiles");
    m_uLampColour = m_shader.uniform("uLampColour");
    glGenBuffers(1, &m_indexBuffer);
    glGenBuffers(1, &m_partIndexBuffer);
    ensureIndexCapacity(4096);
}

ChunkUpload::~ChunkUpload() {
    for (auto& [coord, mesh] : m_meshes) release(mesh);
    glDeleteBuffers(1, &m_indexBuffer);
    glDeleteBuffers(1, &m_partIndexBuffer);
}

void ChunkUpload::ensureIndexCapacity(int quads) {
    if (quads <= m_indexQuads) return;
    int capacity = std::max(m_indexQuads, 4096);
    while (capacity < quads) capacity *= 2;
    // Every quad is (0,1,2) (0,2,3); the mesher orders vertices so this split is the right diagonal.
    std::vector<std::uint32_t> indices(static_cast<std::size_t>(capacity) * 6);
    for (int q = 0; q < capacity; ++q) {
        const std::uint32_t b = static_cast<std::uint32_t>(q) * 4;
        const std::uint32_t quad[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
        std::copy(quad, quad + 6, indices.begin() + static_cast<std::ptrdiff_t>(q) * 6);
    }
    // Unbind any VAO so that binding the element buffer does not modify one.
    glBindVertexArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                 indices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    m_indexQuads = capacity;
}

void ChunkUpload::release(GpuMesh& mesh) {
    ++m_version;
    if (mesh.vao) glDeleteVertexArrays(1, &mesh.vao);
    if (mesh.vbo) glDeleteBuffers(1, &mesh.vbo);
    mesh = {};
}

void ChunkUpload::releaseAll() {
    for (auto& [coord, mesh] : m_meshes) release(mesh);
    m_meshes.clear();
}

void ChunkUpload::upload(GpuMesh& mesh, const world::ChunkMesh& cpu) {
    ++m_version;
    mesh.quads = static_cast<int>(cpu.quadCount());
    // Order quads by face direction and plane, so that draw() skips, before the vertex stage, the faces
    // that look away from the camera and draws a chunk's nearest planes first (docs/ENGINE.md measures
    // what each buys: the second more than the first).
    mesh.order = world::sortByPlane(cpu, m_sorted);
    if (mesh.quads == 0) {
        release(mesh);
        return;
    }
    ensureIndexCapacity(mesh.quads);
    // Each quad into the columns its footprint overlaps (a quad in a column's boundary plane into one
    // of the two: the boxes are closed).
    mesh.spans = {};
    mesh.quadColumns.resize(m_sorted.size() / 4);
    mesh.quadBoxes.resize(m_sorted.size() / 4);
    constexpr int kCell = world::SolidColumns::kCell, kCells = world::SolidColumns::kCells;
    for (std::size_t q = 0; q < m_sorted.size(); q += 4) {
        int x0 = 255, x1 = 0, y0 = 255, y1 = 0, z0 = 255, z1 = 0;
        for (std::size_t k = q; k < q + 4; ++k) {
            const world::ChunkVertex& v = m_sorted[k];
            const int x = world::xOf(v), y = world::yOf(v), z = world::zOf(v);
            x0 = std::min(x0, x), x1 = std::max(x1, x);
            y0 = std::min(y0, y), y1 = std::max(y1, y);
            z0 = std::min(z0, z), z1 = std::max(z1, z);
        }
        const int cx0 = std::min(x0 / kCell, kCells - 1), cz0 = std::min(z0 / kCell, kCells - 1);
        const int cx1 = std::max(cx0, (x1 + kCell - 1) / kCell - 1), cz1 = std::max(cz0, (z1 + kCell - 1) / kCell - 1);
        std::uint16_t columns = 0;
        for (int cz = cz0; cz <= cz1; ++cz) {
            for (int cx = cx0; cx <= cx1; ++cx) {
                columns = static_cast<std::uint16_t>(columns | 1u << world::SolidColumns::index(cx, cz));
                GpuMesh::Span& span = mesh.spans[world::SolidColumns::index(cx, cz)];
                span.low = static_cast<std::uint8_t>(std::min<int>(span.low, y0));
                span.high = static_cast<std::uint8_t>(std::max<int>(span.high, y1));
            }
        }
        mesh.quadColumns[q / 4] = columns;
        mesh.quadBoxes[q / 4] = {
            {static_cast<std::uint8_t>(x0), static_cast<std::uint8_t>(y0), static_cast<std::uint8_t>(z0)},
            {static_cast<std::uint8_t>(x1), static_cast<std::uint8_t>(y1), static_cast<std::uint8_t>(z1)}};
    }
    if (!mesh.vao) {
        glGenVertexArrays(1, &mesh.vao);
        glGenBuffers(1, &mesh.vbo);
        glBindVertexArray(mesh.vao);
        glBindBuffer(GL_ARRAY_BUFFER, mesh.vbo);
        glEnableVertexAttribArray(0);
        glVertexAttribIPointer(0, 4, GL_UNSIGNED_BYTE, sizeof(world::ChunkVertex), nullptr);
        glEnableVertexAttribArray(1);
        glVertexAttribIPointer(1, 4, GL_UNSIGNED_BYTE, sizeof(world::ChunkVertex), reinterpret_cast<const void*>(4));
    } else {
        glBindVertexArray(mesh.vao);
        glBindBuffer(GL_ARRAY_BUFFER, mesh.vbo);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_sorted.size() * sizeof(world::ChunkVertex)),
                 m_sorted.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
}

void ChunkUpload::useShader(const glm::mat4& viewProjection, glm::ivec2 viewport, GLuint atlasArray,
                            const ChunkLighting& light) {
    m_shader.use();
    glUniformMatrix4fv(m_uViewProj, 1, GL_FALSE, &viewProjection[0][0]);
    glUniform3fv(m_uSunDir, 1, &light.sunDirection[0]);
    glUniform3fv(m_uSunColour, 1, &light.sunColour[0]);
    glUniform3fv(m_uSkyColour, 1, &light.skyColour[0]);
    glUniform3fv(m_uFogColor, 1, &light.fogColor[0]);
    glUniform2f(m_uFogRange, light.fogStart, light.fogEnd);
    glUniform2f(m_uHalfViewport, 0.5f * static_cast<float>(std::max(viewport.x, 1)),
                0.5f * static_cast<float>(std::max(viewport.y, 1)));
    glUniform1i(m_uAtlas, 0);
    glUniform1ui(m_uEmissiveTiles, emissiveTiles());
    glUniform3fv(m_uLampColour, 1, &kLampColour[0]);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, atlasArray);
}

void ChunkUpload::uploadPartIndices(const std::vector<std::uint32_t>& indices) {
    if (!indices.empty()) {
        glBindVertexArray(0);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_partIndexBuffer);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                     indices.data(), GL_STREAM_DRAW);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    }
}

void ChunkUpload::bindChunk(const GpuMesh& mesh, const glm::vec3& offset) {
    glUniform3fv(m_uOffset, 1, &offset[0]);
    glBindVertexArray(mesh.vao);
}

long long ChunkUpload::drawPart(std::size_t first, long long count) {
    // The chunk's element buffer is the shared one; its visible quads' indices are elsewhere.
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_partIndexBuffer);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer);
    return count / 3;
}

long long ChunkUpload::drawQuads(int from, int to) {
    glDrawElements(GL_TRIANGLES, (to - from) * 6, GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(static_cast<std::uintptr_t>(from) * 6 * sizeof(std::uint32_t)));
    return 2LL * (to - from);
}

void ChunkUpload::endDraw() { glBindVertexArray(0); }

} // namespace render
