// Yardsticks for the hair solver's speed, used by minecrappy-lab hair-bench and the benchmarks; never by the
// game. Both start from a HairSolver's state and do the same arithmetic per node as its core (time-corrected
// Verlet with damping per second, follow-the-leader length constraints, the nearest-surface push out of the
// host ball), with the host held still:
// - NaiveHairReference is written the way the seed's code is: one object per strand, each a list of node
//   objects (position, last position, length: an array of 3-vectors), scalar loops strand by strand.
// - HairLimitKernel is the same arithmetic as SoA loops over strands with nothing else (no root placement,
//   no path test, no other colliders, no stats, no threads): the practical limit of this machine.
// Build flags: like hair.cpp (-fno-math-errno -fno-trapping-math -ffp-contract=off), so all three are compiled
// alike. Neither must ever be used for anything but timing and cross-checking.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "physics/hair.h"

namespace physics {

class NaiveHairReference {
public:
    explicit NaiveHairReference(const HairSolver& from);
    void step(float dt, int iterations);
    glm::vec3 position(int strand, int node) const {
        return m_strands[static_cast<std::size_t>(strand)].nodes[static_cast<std::size_t>(node)].position;
    }

private:
    struct Node {
        glm::vec3 position{0.0f};
        glm::vec3 lastPosition{0.0f};
        glm::vec3 correction{0.0f}; // velocity correction from the child (dynamic follow-the-leader)
        glm::vec3 predicted{0.0f};
        float length = 0.0f; // rest length of the segment to the previous node
    };
    struct Strand {
        std::vector<Node> nodes;
    };
    std::vector<Strand> m_strands;
    glm::vec3 m_centre{0.0f};
    float m_radius = 0, m_damping = 0, m_gravity = 0, m_lastDt = 0, m_share = 0;
};

class HairLimitKernel {
public:
    explicit HairLimitKernel(const HairSolver& from);
    void step(float dt, int iterations);
    glm::vec3 position(int strand, int node) const {
        const std::size_t i = static_cast<std::size_t>(node) * m_strands + static_cast<std::size_t>(strand);
        return {m_x[i], m_y[i], m_z[i]};
    }

private:
    std::size_t m_strands = 0, m_nodes = 0;
    std::vector<float> m_x, m_y, m_z, m_px, m_py, m_pz, m_cx, m_cy, m_cz, m_scratch;
    glm::vec3 m_centre{0.0f};
    float m_radius = 0, m_segment = 0, m_damping = 0, m_gravity = 0, m_lastDt = 0, m_share = 0;
};

} // namespace physics
