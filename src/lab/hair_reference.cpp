// See hair_reference.h. Compile with the same flags as hair.cpp.
#include "lab/hair_reference.h"

#include "physics/hair_kernels.h"

#include <algorithm>
#include <cmath>

namespace lab {

namespace kernels = physics::kernels;

namespace {
constexpr float kTiny = kernels::kTiny;
constexpr std::size_t kBlock = kernels::kMaxLanes; // as the solver: a block stays in cache through all iterations

// The coefficients of the next substep, as the solver computes them.
struct Coefficients {
    float ratio, damp, accelY;
};
Coefficients coefficients(const HairParams& p, float lastH, double h) {
    const bool fromRest = !(lastH > 0.0f);
    const kernels::StepCoefficients c = kernels::stepCoefficients(static_cast<double>(p.dampingPerSecond), h,
                                                                  fromRest ? h : static_cast<double>(lastH), fromRest);
    return {static_cast<float>(c.ratio), static_cast<float>(c.damp),
            static_cast<float>(-static_cast<double>(p.gravity) * c.accel)};
}
} // namespace

NaiveHairReference::NaiveHairReference(const HairSolver& from) : m_params(from.params()) {
    const int S = from.strands(), N = from.nodesPerStrand();
    m_centre = glm::vec3(from.x()[0], from.y()[0], from.z()[0]) - from.ballRadius() * from.rootDirection(0);
    m_radius = from.ballRadius();
    m_lastDt = from.lastSubstepSeconds();
    m_strands.resize(static_cast<std::size_t>(S));
    for (int s = 0; s < S; ++s) {
        auto& nodes = m_strands[static_cast<std::size_t>(s)].nodes;
        nodes.resize(static_cast<std::size_t>(N));
        for (int n = 0; n < N; ++n) {
            const std::size_t i =
                static_cast<std::size_t>(n) * static_cast<std::size_t>(S) + static_cast<std::size_t>(s);
            Node& node = nodes[static_cast<std::size_t>(n)];
            node.position = {from.x()[i], from.y()[i], from.z()[i]};
            node.lastPosition = {from.prevX()[i], from.prevY()[i], from.prevZ()[i]};
            node.correction = {from.correctionX()[i], from.correctionY()[i], from.correctionZ()[i]};
            node.length = n == 0 ? 0.0f : from.segmentLength();
        }
    }
}

void NaiveHairReference::step(float dt) {
    const int n = hairSubstepsFor(m_params, static_cast<double>(dt));
    for (int k = 0; k < n; ++k) substep(static_cast<double>(dt) / n);
}

void NaiveHairReference::substep(double h) {
    const Coefficients c = coefficients(m_params, m_lastDt, h);
    const glm::vec3 accel(0.0f, c.accelY, 0.0f);
    const HairMethod method = m_params.method;
    const auto ftl = [&](std::vector<Node>& nodes) {
        for (std::size_t n = 1; n < nodes.size(); ++n) {
            Node& node = nodes[n];
            const glm::vec3 parent = nodes[n - 1].position;
            const glm::vec3 d = node.position - parent;
            node.position = parent + d * (node.length / std::sqrt(std::max(glm::dot(d, d), kTiny)));
            glm::vec3 r = node.position - m_centre;
            if (glm::dot(r, r) < m_radius * m_radius) { // inside the ball: onto the contact circle
                const glm::vec3 q = parent - m_centre, a = node.lastPosition - m_centre;
                std::int32_t radial = 0;
                kernels::sphereContact(r.x, r.y, r.z, q.x, q.y, q.z, a.x, a.y, a.z, m_radius, node.length, radial);
                node.position = r + m_centre;
                if (radial != 0) { // no contact circle: out the nearest way
                    kernels::radialOut(r.x, r.y, r.z, m_radius);
                    node.position = r + m_centre;
                }
            }
        }
    };
    for (Strand& strand : m_strands) {
        std::vector<Node>& nodes = strand.nodes;
        nodes[0].lastPosition = nodes[0].position;
        for (std::size_t n = 1; n < nodes.size(); ++n) {
            Node& node = nodes[n];
            const glm::vec3 p = node.position;
            glm::vec3 next = p + ((p - (node.lastPosition - node.correction)) * c.ratio) * c.damp + accel;
            node.lastPosition = p;
            glm::vec3 r = next - m_centre;
            const glm::vec3 q = p - m_centre, b = r - q;
            const float aa = glm::dot(q, q), ab = glm::dot(q, b), bb = glm::dot(b, b), R2 = m_radius * m_radius;
            if (!(glm::dot(r, r) >= R2 && (ab >= 0.0f || aa * bb - ab * ab >= R2 * bb))) { // the path may touch
                if (bb > 0.0625f * R2) {                                                   // fast: out along its path
                    kernels::pushOutAlongPath(r.x, r.y, r.z, q.x, q.y, q.z, m_radius);
                    next = r + m_centre;
                } else if (glm::dot(r, r) < R2) { // slow: the nearest way out
                    next = r * (m_radius / std::sqrt(std::max(glm::dot(r, r), kTiny))) + m_centre;
                }
            }
            node.position = node.predicted = next;
        }
        switch (method) {
        case HairMethod::Ftl:
        case HairMethod::Dftl:
            for (int it = 0; it < m_params.iterations; ++it) ftl(nodes);
            break;
        case HairMethod::Pbd:
        case HairMethod::XpbdSubsteps: {
            const int iterations = method == HairMethod::Pbd ? m_params.iterations : 1;
            for (int it = 0; it < iterations; ++it) {
                for (std::size_t n = 1; n < nodes.size(); ++n) {
                    Node& a = nodes[n - 1];
                    Node& b = nodes[n];
                    const glm::vec3 d = b.position - a.position;
                    const float len = std::sqrt(std::max(glm::dot(d, d), kTiny));
                    const float share = (len - b.length) / len;
                    const float wa = n == 1 ? 0.0f : 0.5f, wb = n == 1 ? 1.0f : 0.5f;
                    a.position += (wa * share) * d;
                    b.position -= (wb * share) * d;
                }
                for (std::size_t n = 1; n < nodes.size(); ++n) {
                    const glm::vec3 r = nodes[n].position - m_centre;
                    const float d2 = glm::dot(r, r);
                    if (d2 < m_radius * m_radius)
                        nodes[n].position = r * (m_radius / std::sqrt(std::max(d2, kTiny))) + m_centre;
                }
            }
            break;
        }
        case HairMethod::Shake: {
            // x_k = q_k - (lambda_k e_k - lambda_{k+1} e_{k+1}), e from the last positions; Newton on the
            // squared lengths, one tridiagonal (Thomas) solve per iteration.
            const std::size_t N = nodes.size();
            const auto e = [&](std::size_t k) { return nodes[k].lastPosition - nodes[k - 1].lastPosition; };
            const auto place = [&] {
                for (std::size_t k = 1; k < N; ++k) {
                    glm::vec3 f = nodes[k].lambda * e(k);
                    if (k + 1 < N) f -= nodes[k + 1].lambda * e(k + 1);
                    nodes[k].position = nodes[k].predicted - f;
                }
            };
            for (Node& node : nodes) node.lambda = 0.0f;
            bool ok = true; // no segment turned more than 60 degrees (see shakeBlock)
            for (int it = 0; it < m_params.iterations; ++it) {
                place();
                for (std::size_t k = 1; k < N; ++k) {
                    const glm::vec3 ek = nodes[k].position - nodes[k - 1].position;
                    const float en = glm::dot(ek, e(k));
                    ok = ok && en > 0.0f && !(4.0f * en * en < glm::dot(ek, ek) * glm::dot(e(k), e(k)));
                    const float F = glm::dot(ek, ek) - nodes[k].length * nodes[k].length;
                    const float diag = -2.0f * (k == 1 ? 1.0f : 2.0f) * glm::dot(ek, e(k));
                    const float sup = k + 1 < N ? 2.0f * glm::dot(ek, e(k + 1)) : 0.0f;
                    const float sub = k > 1 ? 2.0f * glm::dot(ek, e(k - 1)) : 0.0f;
                    float m = diag - sub * (k > 1 ? nodes[k - 1].cp : 0.0f);
                    m = std::abs(m) > kTiny ? m : -kTiny;
                    nodes[k].cp = sup / m;
                    nodes[k].dp = (-F - sub * (k > 1 ? nodes[k - 1].dp : 0.0f)) / m;
                }
                for (std::size_t k = N - 1; k >= 1; --k) {
                    if (k + 1 < N) nodes[k].dp -= nodes[k].cp * nodes[k + 1].dp;
                    nodes[k].lambda += nodes[k].dp;
                }
            }
            if (!ok)
                for (Node& node : nodes) node.lambda = 0.0f;
            place();
            ftl(nodes);
            break;
        }
        case HairMethod::Count:
            break;
        }
        if (method == HairMethod::Dftl) {
            const float limit = (m_radius + 1e-4f) * (m_radius + 1e-4f); // a node lying on the ball: friction
            for (std::size_t n = 1; n + 1 < nodes.size(); ++n) {
                const glm::vec3 r = nodes[n].position - m_centre;
                const float share = glm::dot(r, r) < limit ? 0.0f : m_params.velocityCorrection;
                nodes[n].correction = share * (nodes[n + 1].predicted - nodes[n + 1].position);
            }
        }
    }
    m_lastDt = static_cast<float>(h);
}

HairLimitKernel::HairLimitKernel(const HairSolver& from) : m_params(from.params()) {
    m_strands = static_cast<std::size_t>(from.strands());
    m_nodes = static_cast<std::size_t>(from.nodesPerStrand());
    const std::size_t total = m_strands * m_nodes;
    m_x.assign(from.x(), from.x() + total);
    m_y.assign(from.y(), from.y() + total);
    m_z.assign(from.z(), from.z() + total);
    m_px.assign(from.prevX(), from.prevX() + total);
    m_py.assign(from.prevY(), from.prevY() + total);
    m_pz.assign(from.prevZ(), from.prevZ() + total);
    m_cx.assign(from.correctionX(), from.correctionX() + total);
    m_cy.assign(from.correctionY(), from.correctionY() + total);
    m_cz.assign(from.correctionZ(), from.correctionZ() + total);
    m_scratch.assign(m_nodes * 7 * kBlock, 0.0f); // predicted (3 per node), SHAKE (3 per node + 1)
    m_centre = glm::vec3(from.x()[0], from.y()[0], from.z()[0]) - from.ballRadius() * from.rootDirection(0);
    m_radius = from.ballRadius();
    m_segment = from.segmentLength();
    m_lastDt = from.lastSubstepSeconds();
}

void HairLimitKernel::step(float dt) {
    const int n = hairSubstepsFor(m_params, static_cast<double>(dt));
    for (int k = 0; k < n; ++k) substep(static_cast<double>(dt) / n);
}

void HairLimitKernel::substep(double h) {
    const Coefficients c = coefficients(m_params, m_lastDt, h);
    float* X = m_x.data();
    float* Y = m_y.data();
    float* Z = m_z.data();
    float* PX = m_px.data();
    float* PY = m_py.data();
    float* PZ = m_pz.data();
    float* CX = m_cx.data();
    float* CY = m_cy.data();
    float* CZ = m_cz.data();
    const std::size_t S = m_strands, N = m_nodes;
    const float L = m_segment, R = m_radius;
    const glm::vec3 C = m_centre;
    const HairMethod method = m_params.method;
    for (std::size_t lo = 0; lo < S; lo += kBlock) {
        const std::size_t hi = std::min(S, lo + kBlock);
        const auto q = [&](std::size_t n, std::size_t axis) { return m_scratch.data() + (n * 3 + axis) * kBlock; };
        for (std::size_t s = lo; s < hi; ++s) PX[s] = X[s], PY[s] = Y[s], PZ[s] = Z[s]; // the still roots' history
        for (std::size_t n = 1; n < N; ++n) {
            const std::size_t o = n * S;
            kernels::integrateLevel<true>(X + o, Y + o, Z + o, PX + o, PY + o, PZ + o, CX + o, CY + o, CZ + o, q(n, 0),
                                          q(n, 1), q(n, 2), lo, hi, glm::vec3(0.0f), c.ratio, c.damp, c.accelY, C, C,
                                          R);
        }
        const auto ftlPass = [&] {
            for (std::size_t n = 1; n < N; ++n)
                kernels::ftlLevel<true>(X + n * S, Y + n * S, Z + n * S, X + n * S - S, Y + n * S - S, Z + n * S - S,
                                        PX + n * S, PY + n * S, PZ + n * S, lo, hi, L, C, C, R);
        };
        kernels::constrain(
            method, m_params.iterations, ftlPass,
            [&] {
                for (std::size_t n = 1; n < N; ++n)
                    kernels::pbdLevel(X + n * S - S, Y + n * S - S, Z + n * S - S, X + n * S, Y + n * S, Z + n * S, lo,
                                      hi, L, n == 1);
                for (std::size_t n = 1; n < N; ++n)
                    kernels::radialPushLevel(X + n * S, Y + n * S, Z + n * S, lo, hi, C, R);
            },
            [&] {
                kernels::shakeBlock(X, Y, Z, PX, PY, PZ, m_scratch.data(), m_scratch.data() + N * 3 * kBlock, S, N, lo,
                                    hi, kBlock, L, m_params.iterations);
                ftlPass();
            });
        if (method == HairMethod::Dftl) {
            for (std::size_t n = 1; n + 1 < N; ++n) {
                const std::size_t o = n * S, oc = o + S;
                kernels::correctParentVelocity(CX + o, CY + o, CZ + o, X + oc, Y + oc, Z + oc, q(n + 1, 0), q(n + 1, 1),
                                               q(n + 1, 2), lo, hi, m_params.velocityCorrection, X + o, Y + o, Z + o, C,
                                               R);
            }
        }
    }
    m_lastDt = static_cast<float>(h);
}

} // namespace lab
