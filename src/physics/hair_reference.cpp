// See hair_reference.h. Compile with the same flags as hair.cpp.
#include "physics/hair_reference.h"

#include <algorithm>
#include <cmath>

namespace physics {

namespace {
constexpr float kTiny = 1e-30f;
constexpr std::size_t kBlock = 64; // as the solver: a block stays in cache through all iterations
} // namespace

NaiveHairReference::NaiveHairReference(const HairSolver& from) {
    const int S = from.strands(), N = from.nodesPerStrand();
    m_centre = glm::vec3(from.x()[0], from.y()[0], from.z()[0]) - from.ballRadius() * from.rootDirection(0);
    m_radius = from.ballRadius();
    m_damping = from.params().dampingPerSecond;
    m_gravity = from.params().gravity;
    m_share = from.params().velocityCorrection;
    m_strands.resize(static_cast<std::size_t>(S));
    for (int s = 0; s < S; ++s) {
        auto& nodes = m_strands[static_cast<std::size_t>(s)].nodes;
        nodes.resize(static_cast<std::size_t>(N));
        for (int n = 0; n < N; ++n) {
            const std::size_t i =
                static_cast<std::size_t>(n) * static_cast<std::size_t>(S) + static_cast<std::size_t>(s);
            nodes[static_cast<std::size_t>(n)] = {{from.x()[i], from.y()[i], from.z()[i]},
                                                  {from.prevX()[i], from.prevY()[i], from.prevZ()[i]},
                                                  glm::vec3(0.0f),
                                                  glm::vec3(0.0f),
                                                  n == 0 ? 0.0f : from.segmentLength()};
        }
    }
}

void NaiveHairReference::step(float dt, int iterations) {
    const float hPrev = m_lastDt > 0.0f ? m_lastDt : dt;
    const float ratio = dt / hPrev, damp = std::exp(-m_damping * dt);
    const glm::vec3 accel(0.0f, -m_gravity * dt * (dt + hPrev) * 0.5f, 0.0f);
    for (Strand& strand : m_strands) {
        for (std::size_t n = 1; n < strand.nodes.size(); ++n) {
            Node& node = strand.nodes[n];
            const glm::vec3 p = node.position;
            node.position = p + (p - (node.lastPosition - node.correction)) * ratio * damp + accel;
            node.lastPosition = p;
            node.predicted = node.position;
        }
        for (int it = 0; it < iterations; ++it) {
            for (std::size_t n = 1; n < strand.nodes.size(); ++n) {
                Node& node = strand.nodes[n];
                const glm::vec3 parent = strand.nodes[n - 1].position;
                const glm::vec3 d = node.position - parent;
                glm::vec3 p = parent + d * (node.length / std::sqrt(std::max(glm::dot(d, d), kTiny)));
                const glm::vec3 r = p - m_centre;
                const float d2 = glm::dot(r, r);
                if (d2 < m_radius * m_radius) p = m_centre + r * (m_radius / std::sqrt(std::max(d2, kTiny)));
                node.position = p;
            }
        }
        for (std::size_t n = 1; n + 1 < strand.nodes.size(); ++n)
            strand.nodes[n].correction = m_share * (strand.nodes[n + 1].predicted - strand.nodes[n + 1].position);
    }
    m_lastDt = dt;
}

HairLimitKernel::HairLimitKernel(const HairSolver& from) {
    m_strands = static_cast<std::size_t>(from.strands());
    m_nodes = static_cast<std::size_t>(from.nodesPerStrand());
    const std::size_t total = m_strands * m_nodes;
    m_x.assign(from.x(), from.x() + total);
    m_y.assign(from.y(), from.y() + total);
    m_z.assign(from.z(), from.z() + total);
    m_px.assign(from.prevX(), from.prevX() + total);
    m_py.assign(from.prevY(), from.prevY() + total);
    m_pz.assign(from.prevZ(), from.prevZ() + total);
    m_cx.assign(total, 0.0f);
    m_cy.assign(total, 0.0f);
    m_cz.assign(total, 0.0f);
    m_scratch.assign(m_nodes * 3 * kBlock, 0.0f);
    m_share = from.params().velocityCorrection;
    m_centre = glm::vec3(from.x()[0], from.y()[0], from.z()[0]) - from.ballRadius() * from.rootDirection(0);
    m_radius = from.ballRadius();
    m_segment = from.segmentLength();
    m_damping = from.params().dampingPerSecond;
    m_gravity = from.params().gravity;
}

namespace {

void verletLevel(float* __restrict X, float* __restrict Y, float* __restrict Z, float* __restrict PX,
                 float* __restrict PY, float* __restrict PZ, const float* __restrict CX, const float* __restrict CY,
                 const float* __restrict CZ, float* __restrict QX, float* __restrict QY, float* __restrict QZ,
                 std::size_t lo, std::size_t hi, float ratio, float damp, float accelY) {
    for (std::size_t s = lo; s < hi; ++s) {
        const float x = X[s], y = Y[s], z = Z[s];
        X[s] = QX[s - lo] = x + (x - (PX[s] - CX[s])) * ratio * damp;
        Y[s] = QY[s - lo] = y + (y - (PY[s] - CY[s])) * ratio * damp + accelY;
        Z[s] = QZ[s - lo] = z + (z - (PZ[s] - CZ[s])) * ratio * damp;
        PX[s] = x, PY[s] = y, PZ[s] = z;
    }
}

void correctLevel(float* __restrict CX, float* __restrict CY, float* __restrict CZ, const float* __restrict X,
                  const float* __restrict Y, const float* __restrict Z, const float* __restrict QX,
                  const float* __restrict QY, const float* __restrict QZ, std::size_t lo, std::size_t hi, float share) {
    for (std::size_t s = lo; s < hi; ++s) {
        CX[s] = share * (QX[s - lo] - X[s]);
        CY[s] = share * (QY[s - lo] - Y[s]);
        CZ[s] = share * (QZ[s - lo] - Z[s]);
    }
}

void constrainPushLevel(float* __restrict X, float* __restrict Y, float* __restrict Z, const float* __restrict XP,
                        const float* __restrict YP, const float* __restrict ZP, std::size_t lo, std::size_t hi, float L,
                        float cx, float cy, float cz, float R) {
    const float R2 = R * R;
    for (std::size_t s = lo; s < hi; ++s) {
        const float dx = X[s] - XP[s], dy = Y[s] - YP[s], dz = Z[s] - ZP[s];
        const float k = L / std::sqrt(std::max(dx * dx + dy * dy + dz * dz, kTiny));
        const float x = XP[s] + dx * k - cx, y = YP[s] + dy * k - cy, z = ZP[s] + dz * k - cz;
        const float d2 = x * x + y * y + z * z;
        const float scale = R / std::sqrt(std::max(d2, kTiny));
        const float out = d2 < R2 ? scale : 1.0f;
        X[s] = x * out + cx, Y[s] = y * out + cy, Z[s] = z * out + cz;
    }
}

} // namespace

void HairLimitKernel::step(float dt, int iterations) {
    const float hPrev = m_lastDt > 0.0f ? m_lastDt : dt;
    const float ratio = dt / hPrev, damp = std::exp(-m_damping * dt);
    const float accelY = -m_gravity * dt * (dt + hPrev) * 0.5f;
    float* X = m_x.data();
    float* Y = m_y.data();
    float* Z = m_z.data();
    float* PX = m_px.data();
    float* PY = m_py.data();
    float* PZ = m_pz.data();
    const std::size_t S = m_strands;
    for (std::size_t lo = 0; lo < S; lo += kBlock) {
        const std::size_t hi = std::min(S, lo + kBlock);
        const auto q = [&](std::size_t n, std::size_t axis) { return m_scratch.data() + (n * 3 + axis) * kBlock; };
        for (std::size_t n = 1; n < m_nodes; ++n) {
            const std::size_t o = n * S;
            verletLevel(X + o, Y + o, Z + o, PX + o, PY + o, PZ + o, m_cx.data() + o, m_cy.data() + o, m_cz.data() + o,
                        q(n, 0), q(n, 1), q(n, 2), lo, hi, ratio, damp, accelY);
        }
        for (int it = 0; it < iterations; ++it) {
            for (std::size_t n = 1; n < m_nodes; ++n) {
                const std::size_t o = n * S;
                constrainPushLevel(X + o, Y + o, Z + o, X + o - S, Y + o - S, Z + o - S, lo, hi, m_segment, m_centre.x,
                                   m_centre.y, m_centre.z, m_radius);
            }
        }
        for (std::size_t n = 1; n + 1 < m_nodes; ++n) {
            const std::size_t o = n * S;
            correctLevel(m_cx.data() + o, m_cy.data() + o, m_cz.data() + o, X + o + S, Y + o + S, Z + o + S,
                         q(n + 1, 0), q(n + 1, 1), q(n + 1, 2), lo, hi, m_share);
        }
    }
    m_lastDt = dt;
}

} // namespace physics
