#include "game/hair_budget.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "game/game_state.h"

namespace game {

namespace {
float hairReach(const HairBall& b) { return b.def().radius + b.def().hair.strandLength; }
} // namespace

void findHairNeighbours(const std::vector<HairBall>& balls, HairNeighbours& out) {
    const std::size_t n = balls.size();
    // Sort and sweep along x: a pair can touch only if their x extents (centre +- hair reach) overlap.
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        const float ka = balls[a].centre().x - hairReach(balls[a]), kb = balls[b].centre().x - hairReach(balls[b]);
        return ka < kb || (ka == kb && a < b);
    });
    std::vector<std::vector<std::uint32_t>> near(n);
    for (std::size_t k = 0; k < n; ++k) {
        const HairBall& a = balls[order[k]];
        const float aEnd = a.centre().x + hairReach(a);
        for (std::size_t m = k + 1; m < n; ++m) {
            const HairBall& b = balls[order[m]];
            if (b.centre().x - hairReach(b) >= aEnd) break;
            const float d = glm::length(a.centre() - b.centre());
            // Each direction on its own: a long-haired ball may reach a short-haired one but not back.
            if (d < hairReach(a) + b.def().radius) near[order[k]].push_back(order[m]);
            if (d < hairReach(b) + a.def().radius) near[order[m]].push_back(order[k]);
        }
    }
    out.offsets.assign(n + 1, 0);
    out.colliders.clear();
    out.index.clear();
    for (std::size_t i = 0; i < n; ++i) {
        // Ascending index order, as the solver received them before the broadphase: pushes are applied in
        // this order, so it keeps the results bit for bit.
        std::sort(near[i].begin(), near[i].end());
        for (const std::uint32_t j : near[i]) {
            out.colliders.push_back(balls[j].collider());
            out.index.push_back(j);
        }
        out.offsets[i + 1] = static_cast<std::uint32_t>(out.colliders.size());
    }
}

std::int64_t hairCost(const HairBall& ball, int strands, std::size_t neighbours, double tickSeconds) {
    const physics::HairParams& h = ball.def().hair;
    const std::int64_t perSubstep = physics::hairProjectionsPerNode(h) / h.substeps;
    return static_cast<std::int64_t>(strands) * (h.nodesPerStrand - 1) * perSubstep *
           physics::hairSubstepsFor(h, tickSeconds) * static_cast<std::int64_t>(2 + neighbours);
}

std::vector<int> shareHairBudget(const GameState& s, const HairNeighbours& nb, const glm::vec3& eye,
                                 const glm::vec3& forward, std::int64_t budget, double tickSeconds) {
    const std::size_t n = s.hairBalls.size();
    std::vector<int> wanted(n), share(n);
    std::vector<double> weight(n, 0.0);
    std::int64_t total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const HairBall& b = s.hairBalls[i];
        wanted[i] = activeStrandsFor(b, eye, s.def.hairDetail);
        share[i] = wanted[i];
        if (b.solver().sleeping()) {
            share[i] = b.solver().activeStrands(); // asleep: no cost, and a change would wake it
            continue;
        }
        const glm::vec3 to = b.centre() - eye;
        const float d = glm::length(to);
        // In view (within about 60 degrees of the view direction) or close enough to fill it: full weight.
        const bool seen = d < 2.0f * hairReach(b) || glm::dot(to, forward) > 0.5f * d;
        weight[i] = (seen ? 1.0 : 0.25) / (1.0 + static_cast<double>(d) * d / 256.0);
        total += hairCost(b, wanted[i], nb.offsets[i + 1] - nb.offsets[i], tickSeconds);
    }
    if (total <= budget) return share;

    // Over budget: ball i gets min(wanted, floor(k weight_i wanted)) strands; the largest k that fits is
    // found by bisection (the total only grows with k).
    const auto sharesAt = [&](double k, std::vector<int>& out) {
        std::int64_t cost = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (weight[i] == 0.0) continue;
            const double want = static_cast<double>(wanted[i]);
            out[i] = static_cast<int>(std::min(want, std::floor(k * weight[i] * want)));
            cost += hairCost(s.hairBalls[i], out[i], nb.offsets[i + 1] - nb.offsets[i], tickSeconds);
        }
        return cost;
    };
    double lo = 0.0, hi = 1.0;
    for (std::size_t i = 0; i < n; ++i) {
        if (weight[i] > 0.0) hi = std::max(hi, 1.0 / weight[i]);
    }
    std::vector<int> trial = share;
    for (int it = 0; it < 48; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (sharesAt(mid, trial) <= budget) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    sharesAt(lo, share);
    return share;
}

} // namespace game
