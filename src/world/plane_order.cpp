#include "world/plane_order.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace world {

PlaneOrder sortByPlane(const ChunkMesh& mesh, std::vector<ChunkVertex>& sorted) {
    constexpr int kPlanes = PlaneOrder::kPlanes;
    // Key of a quad: face * kPlanes + plane, from its first vertex (all four share the plane).
    const auto keyOf = [&](std::size_t q) {
        const ChunkVertex& v = mesh.vertices[q * 4];
        const int face = faceOf(v);
        const int axis = face / 2;
        const int plane = axis == 0 ? xOf(v) : axis == 1 ? yOf(v) : zOf(v);
        if (face >= kFaceCount || plane >= kPlanes) throw std::invalid_argument("sortByPlane: vertex out of range");
        return face * kPlanes + PlaneOrder::slotOf(face, plane);
    };
    PlaneOrder order;
    std::array<int, kFaceCount * kPlanes + 1> next{};
    for (std::size_t q = 0; q < mesh.quadCount(); ++q) ++next[static_cast<std::size_t>(keyOf(q)) + 1];
    for (std::size_t k = 1; k < next.size(); ++k) next[k] += next[k - 1];
    order.start = next;
    sorted.resize(mesh.quadCount() * 4);
    for (std::size_t q = 0; q < mesh.quadCount(); ++q) {
        const auto slot = static_cast<std::size_t>(next[static_cast<std::size_t>(keyOf(q))]++);
        std::memcpy(&sorted[slot * 4], &mesh.vertices[q * 4], 4 * sizeof(ChunkVertex));
    }
    return order;
}

PlaneOrder::Range PlaneOrder::visible(int face, float t) const {
    // Clamped as floats first, so that any camera position converts to an int safely.
    const float c = std::clamp(t, -1.0f, static_cast<float>(kPlanes));
    // Seen from the front are planes p <= floor(t) of a positive face and p >= ceil(t) of a negative
    // one: in slot order, both a run that ends at the last slot.
    const int from = face % 2 == 0 ? std::clamp(kPlanes - 1 - static_cast<int>(std::floor(c)), 0, kPlanes)
                                   : std::clamp(static_cast<int>(std::ceil(c)), 0, kPlanes);
    return {at(face, from), at(face, kPlanes)}; // empty when from == kPlanes
}

} // namespace world
