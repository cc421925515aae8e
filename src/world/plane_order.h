// The order a chunk's quads are drawn in: by face direction and by plane, nearest first, so that the
// renderer draws only the planes whose faces can face the camera. It reorders the quads a mesh holds and
// never changes one; it knows nothing of GL (render/chunk_upload.cpp uploads the sorted vertices).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "world/chunk.h"
#include "world/chunk_vertex.h"

namespace world {

// A mesh's quads ordered by face direction and, within a direction, by the plane they lie in (their
// chunk-local coordinate along the face's normal, 0..32), nearest first to a camera on the side the
// faces look to (descending planes for a positive face, ascending for a negative one), so that the
// depth test rejects what a nearer plane of the same chunk hides before it is shaded. A face is seen
// from the front only from the side its normal points to, so of a chunk whose extent holds the camera
// along an axis a renderer draws only the planes on the camera's side, leaving out before the vertex
// stage what back-face culling would discard after it.
struct PlaneOrder {
    static constexpr int kPlanes = kChunkSize + 1;
    // Slot of plane p within face f's quads: nearest first, as above.
    static constexpr int slotOf(int face, int plane) { return face % 2 == 0 ? kPlanes - 1 - plane : plane; }
    // Quads of face f in slot k: [start[f * kPlanes + k], start[f * kPlanes + k + 1]).
    std::array<int, kFaceCount * kPlanes + 1> start{};
    // start[face * kPlanes + slot]; slot kPlanes is the next face's first (or the end).
    int at(int face, int slot) const {
        return start[static_cast<std::size_t>(face) * kPlanes + static_cast<std::size_t>(slot)];
    }
    // Quads [first, last) of face f that can face a camera at coordinate t along the face's axis,
    // relative to the chunk's origin: planes p < t for a positive face, p > t for a negative one, and
    // at most the plane through the camera besides (seen edge-on, so back-face culling drops it).
    struct Range {
        int first = 0, last = 0;
    };
    Range visible(int face, float t) const;
};
// Writes mesh's quads to `sorted` (resized to fit) in plane order, stably, and returns the order.
PlaneOrder sortByPlane(const ChunkMesh& mesh, std::vector<ChunkVertex>& sorted);

} // namespace world
