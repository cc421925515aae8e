// Yardsticks for the hair solver's speed, used by minecrappy-lab hair-bench and the benchmarks; never by the
// game. Both start from a HairSolver's state (its method, iterations and substeps too) and do the same
// arithmetic per node as its core (Verlet with exact damping, the path-aware push out of the host ball, the
// method's length constraints and contacts, dynamic FTL's velocity correction), with the host held still and
// no other collider:
// - NaiveHairReference is written the way the seed's code is: one object per strand, each a list of node
//   objects (position, last position, length: an array of 3-vectors), scalar loops strand by strand.
// - HairLimitKernel is the solver's own level loops (physics/hair_kernels.h) with nothing else around them (no
//   root placement, no other colliders or blocks, no stats, no sleep, no threads): the practical limit.
// With the same input all three give the same positions: the limit kernel bit for bit, the naive reference to
// rounding (its SHAKE solve sums in another order); tests/physics/test_hair_methods.cpp checks it.
// Build flags: like hair.cpp (-fno-math-errno -fno-trapping-math -ffp-contract=off), so all three are compiled
// alike. Neither must ever be used for anything but timing and cross-checking.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "physics/hair.h"

namespace lab {

using physics::HairMethod;
using physics::HairParams;
using physics::HairSolver;

class NaiveHairReference {
public:
    explicit NaiveHairReference(const HairSolver& from);
    void step(float dt);
    glm::vec3 position(int strand, int node) const {
        return m_strands[static_cast<std::size_t>(strand)].nodes[static_cast<std::size_t>(node)].position;
    }

private:
    struct Node {
        glm::vec3 position{0.0f};
        glm::vec3 lastPosition{0.0f};
        glm::vec3 correction{0.0f}; // velocity correction from the child (dynamic follow-the-leader)
        glm::vec3 predicted{0.0f};
        float length = 0.0f;                       // rest length of the segment to the previous node
        float lambda = 0.0f, cp = 0.0f, dp = 0.0f; // SHAKE: multiplier of that segment, Thomas sweep values
    };
    struct Strand {
        std::vector<Node> nodes;
    };
    void substep(double h); // s
    std::vector<Strand> m_strands;
    HairParams m_params;
    glm::vec3 m_centre{0.0f};
    float m_radius = 0, m_lastDt = 0;
};

class HairLimitKernel {
public:
    explicit HairLimitKernel(const HairSolver& from);
    void step(float dt);
    glm::vec3 position(int strand, int node) const {
        const std::size_t i = static_cast<std::size_t>(node) * m_strands + static_cast<std::size_t>(strand);
        return {m_x[i], m_y[i], m_z[i]};
    }

private:
    void substep(double h); // s
    std::size_t m_strands = 0, m_nodes = 0;
    std::vector<float> m_x, m_y, m_z, m_px, m_py, m_pz, m_cx, m_cy, m_cz, m_scratch;
    HairParams m_params;
    glm::vec3 m_centre{0.0f};
    float m_radius = 0, m_segment = 0, m_lastDt = 0;
};

} // namespace lab
