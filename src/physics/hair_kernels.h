// The hair methods' per-node arithmetic, shared by the solver (hair.cpp) and the speed yardstick
// (hair_reference.cpp's limit kernel), so the yardstick times exactly what the solver computes. Internal to
// physics: nothing outside those two files includes it. Every loop runs over strands with unit stride at one
// node level (node-major SoA, index = strand), with no dependence between iterations, so it vectorises;
// that is why collisions are written as selects, not branches. Compile the includers with hair.cpp's flags
// (-fno-math-errno -ffp-contract=off), or the vector and scalar code round differently.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "physics/hair.h" // HairMethod

namespace physics::kernels {

// One substep's constraint passes by method, shared by the solver and the limit kernel so that both run the
// same sequence: ftl and dftl, `iterations` follow-the-leader passes; pbd, `iterations` PBD iterations and
// xpbd-substeps one; shake, its solve (which ends with its own follow-the-leader pass).
template <typename FtlPass, typename PbdIteration, typename ShakeSolve>
inline void constrain(HairMethod method, int iterations, const FtlPass& ftlPass, const PbdIteration& pbdIteration,
                      const ShakeSolve& shakeSolve) {
    switch (method) {
    case HairMethod::Ftl:
    case HairMethod::Dftl:
        for (int it = 0; it < iterations; ++it) ftlPass();
        break;
    case HairMethod::Pbd:
    case HairMethod::XpbdSubsteps:
        for (int it = 0, n = method == HairMethod::Pbd ? iterations : 1; it < n; ++it) pbdIteration();
        break;
    case HairMethod::Shake:
        shakeSolve();
        break;
    case HairMethod::Count:
        break;
    }
}

inline constexpr float kTiny = 1e-30f;
inline constexpr std::size_t kMaxLanes = 64; // strands a level loop takes at once (the solver's block)

// Step coefficients of the exact exponential integrator for v' = a - d (v - V) over one step h after a step
// hPrev (V: the host's velocity, taken constant over the two steps). With D = x - prev and dH the host's move
// over the previous step, the exact position after h is
//   x' = x + r dH + (D - dH) keep + a accel,   r = h / hPrev,
//   keep  = e^{-d hPrev} phi1(h) / phi1(hPrev),
//   accel = phi2(h) + phi1(h) (phi1(hPrev) - e^{-d hPrev} phi2(hPrev) / phi1(hPrev)),
// phi1(h) = (1 - e^{-d h}) / d, phi2(h) = (h - phi1(h)) / d: the relative velocity decays as e^{-d t} and
// approaches a / d exactly, whatever the steps. d = 0 gives the time-corrected Verlet step (keep = r,
// accel = h (h + hPrev) / 2). `fromRest`: no history (the first step, or after sleep): the node starts with
// velocity D / h, and x' = x + (D / h) phi1(h) + a phi2(h).
struct StepCoefficients {
    double ratio = 1; // r
    double damp = 1;  // keep / r: the factor verletStep applies to the ratio-scaled displacement
    double accel = 0; // multiplies the acceleration
};

inline double phi1(double d, double h) {
    const double x = d * h;
    return x < 1e-3 ? h * (1.0 - x * (1.0 / 2.0 - x * (1.0 / 6.0 - x / 24.0))) : -std::expm1(-x) / d;
}
inline double phi2(double d, double h) {
    const double x = d * h;
    return x < 1e-3 ? h * h * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0 - x / 120.0))) : (h - phi1(d, h)) / d;
}

inline StepCoefficients stepCoefficients(double d, double h, double hPrev, bool fromRest) {
    StepCoefficients c;
    if (fromRest) {
        c.ratio = 1.0;
        c.damp = phi1(d, h) / h;
        c.accel = phi2(d, h);
        return c;
    }
    const double e = std::exp(-d * hPrev), p1 = phi1(d, h), p1Prev = phi1(d, hPrev);
    c.ratio = h / hPrev;
    c.damp = e * p1 / p1Prev / c.ratio;
    c.accel = phi2(d, h) + p1 * (p1Prev - e * phi2(d, hPrev) / p1Prev);
    return c;
}

// p (relative to the sphere's centre, in/out) came from q (relative too). If the path q -> p enters the
// sphere, p goes onto the tangent plane at the entry point and from there onto the surface: out on the side it
// came from, keeping its sliding motion, never through to the far side. If q was already inside (the sphere
// moved onto it), p goes out the nearest way.
inline void pushOutAlongPath(float& px, float& py, float& pz, float qx, float qy, float qz, float r) {
    const float r2 = r * r;
    const float bx = px - qx, by = py - qy, bz = pz - qz;
    const float aa = qx * qx + qy * qy + qz * qz;
    const float ab = qx * bx + qy * by + qz * bz;
    const float bb = bx * bx + by * by + bz * bz;
    const float disc = ab * ab - bb * (aa - r2);
    // Smaller root of bb t^2 + 2 ab t + (aa - r2) = 0 in the form that does not cancel when bb is small.
    const float den = std::max(std::sqrt(std::max(disc, 0.0f)) - ab, kTiny);
    const float t = (aa - r2) / den;
    const bool entry = (aa >= r2) & (ab < 0.0f) & (disc >= 0.0f) & (t <= 1.0f);
    const float mx = entry ? qx + t * bx : px;
    const float my = entry ? qy + t * by : py;
    const float mz = entry ? qz + t * bz : pz;
    const float inv = 1.0f / std::sqrt(std::max(mx * mx + my * my + mz * mz, kTiny));
    const float nx = mx * inv, ny = my * inv, nz = mz * inv;
    const float pen = r - (px * nx + py * ny + pz * nz);
    const float push = std::max(pen, 0.0f);
    const float tx = px + push * nx, ty = py + push * ny, tz = pz + push * nz;
    // The tangent plane keeps a sliding node's motion but reaches far from a deep one; back onto the surface
    // along the same direction, so the node stays near where it entered (and off any neighbouring collider).
    const float back = r / std::sqrt(std::max(tx * tx + ty * ty + tz * tz, kTiny));
    const float k = pen > 0.0f ? back : 1.0f;
    px = tx * k;
    py = ty * k;
    pz = tz * k;
}

// A node (x, y, z) one segment L from its parent (px, py, pz), all relative to a sphere's centre, radius R.
// If the node is inside, it goes to the circle where the sphere's surface meets the parent's sphere of radius
// L: out of the collider with its segment's length kept. Of the circle it takes the point nearest (ax, ay, az),
// where the node was at the step's start: a node in contact stays put unless its parent drags it (friction;
// without it, hair lying on a collider creeps sideways a little every step and never comes to rest). Where the
// two spheres do not meet (|R - L| > |parent| or |parent| > R + L, i.e. the parent deep inside) or both that
// point and the node are on the axis through the parent, the node goes out radially and the length gives.
inline void sphereContact(float& x, float& y, float& z, float px, float py, float pz, float ax, float ay, float az,
                          float R, float L, std::int32_t& radial) {
    const float d2 = x * x + y * y + z * z;
    const float dp2 = px * px + py * py + pz * pz;
    const float dpInv = 1.0f / std::sqrt(std::max(dp2, kTiny));
    const float ux = px * dpInv, uy = py * dpInv, uz = pz * dpInv;
    const float a = (R * R - L * L + dp2) * 0.5f * dpInv; // the circle's plane, from the centre along u
    const float rho2 = R * R - a * a;
    // The direction within the circle's plane: from where the node was (friction), or where it is when that
    // lies on the axis (a strand pointing straight out); taken twice off the axis, so rounding in a short
    // perpendicular part cannot tilt the point off the surface.
    const float alongA = ax * ux + ay * uy + az * uz, alongX = x * ux + y * uy + z * uz;
    const float pax = ax - alongA * ux, pay = ay - alongA * uy, paz = az - alongA * uz;
    const float pxx = x - alongX * ux, pxy = y - alongX * uy, pxz = z - alongX * uz;
    const bool fromAnchor = pax * pax + pay * pay + paz * paz > 1e-6f * (ax * ax + ay * ay + az * az);
    const float vx = fromAnchor ? pax : pxx, vy = fromAnchor ? pay : pxy, vz = fromAnchor ? paz : pxz;
    const float again = vx * ux + vy * uy + vz * uz;
    const float wx = vx - again * ux, wy = vy - again * uy, wz = vz - again * uz;
    const float w2 = wx * wx + wy * wy + wz * wz;
    const float k = std::sqrt(std::max(rho2, 0.0f) / std::max(w2, kTiny));
    const bool circle = (rho2 >= 0.0f) & (w2 > 1e-12f * L * L);
    const bool inside = d2 < R * R;
    const bool onCircle = inside & circle;
    x = onCircle ? a * ux + k * wx : x;
    y = onCircle ? a * uy + k * wy : y;
    z = onCircle ? a * uz + k * wz : z;
    // No circle: the caller moves the node out radially (radialOut), rarely needed, so kept out of this loop.
    const bool noCircle = inside & !circle;
    radial = noCircle ? 1 : 0;
}

// Out of a sphere radially, onto its surface: the contact's fallback (see sphereContact).
inline void radialOut(float& x, float& y, float& z, float R) {
    const float k = R / std::sqrt(std::max(x * x + y * y + z * z, kTiny));
    x *= k, y *= k, z *= k;
}

// Verlet with the exact damping of StepCoefficients (the velocity correction acts as a shift of the history),
// then, when `host`, the path-aware push out of the host ball (which moved from oldCentre to centre). The
// predicted positions go to Q (block-relative) for the velocity correction and SHAKE.
template <bool host>
inline void integrateLevel(float* __restrict X, float* __restrict Y, float* __restrict Z, float* __restrict PX,
                           float* __restrict PY, float* __restrict PZ, const float* __restrict CX,
                           const float* __restrict CY, const float* __restrict CZ, float* __restrict QX,
                           float* __restrict QY, float* __restrict QZ, std::size_t lo, std::size_t hi,
                           glm::vec3 hostMove, float ratio, float damp, float accelY, glm::vec3 oldCentre,
                           glm::vec3 centre, float R) {
    const float hmx = hostMove.x, hmy = hostMove.y, hmz = hostMove.z;
    const float ox = oldCentre.x, oy = oldCentre.y, oz = oldCentre.z, cx = centre.x, cy = centre.y, cz = centre.z;
    const float R2 = R * R;
    // Per lane: 1 where the path may touch the ball; 1 where the node moved more than a quarter of the radius
    // (kept apart: a reduction inside the loop stops it vectorising).
    std::int32_t maybe[kMaxLanes], fast[kMaxLanes]; // 0 or 1; OR-reduced, which vectorises (max does not)
    for (std::size_t s = lo; s < hi; ++s) {
        const float x = X[s], y = Y[s], z = Z[s];
        const float dx = x - (PX[s] - CX[s]), dy = y - (PY[s] - CY[s]), dz = z - (PZ[s] - CZ[s]);
        const float carriedX = hmx * ratio, carriedY = hmy * ratio, carriedZ = hmz * ratio;
        const float nx = x + carriedX + (dx * ratio - carriedX) * damp;
        const float ny = y + carriedY + (dy * ratio - carriedY) * damp + accelY;
        const float nz = z + carriedZ + (dz * ratio - carriedZ) * damp;
        PX[s] = x, PY[s] = y, PZ[s] = z;
        X[s] = nx, Y[s] = ny, Z[s] = nz;
        QX[s - lo] = nx, QY[s - lo] = ny, QZ[s - lo] = nz; // the pushes below update what they move
        if constexpr (host) {
            // Could the path from q (old, relative to the old centre) to p (new, relative to the new centre) touch
            // the ball? Not if p is outside and the path moves away or passes wide of it (closest approach of the
            // segment's line, aa - ab^2 / bb >= R^2, written without a division).
            const float px = nx - cx, py = ny - cy, pz = nz - cz, qx = x - ox, qy = y - oy, qz = z - oz;
            const float bx = px - qx, by = py - qy, bz = pz - qz;
            const float aa = qx * qx + qy * qy + qz * qz, ab = qx * bx + qy * by + qz * bz,
                        bb = bx * bx + by * by + bz * bz, pp = px * px + py * py + pz * pz;
            const bool clear = (pp >= R2) & ((ab >= 0.0f) | (aa * bb - ab * ab >= R2 * bb));
            maybe[s - lo] = clear ? 0 : 1;
            fast[s - lo] = bb > 0.0625f * R2 ? 1 : 0;
        }
    }
    if constexpr (host) {
        std::int32_t near = 0, anyFast = 0;
        for (std::size_t l = 0; l < hi - lo; ++l) near |= maybe[l];
        for (std::size_t l = 0; l < hi - lo; ++l) anyFast |= maybe[l] & fast[l];
        // Where a lane may touch: a slow node (moved under R / 4) cannot have crossed the ball, so the nearest
        // way out (radially) is its own side; a fast one is pushed out along its path. The path arithmetic
        // (three square roots, three divisions) runs only for levels with a fast lane near the ball.
        if (near != 0) {
            for (std::size_t s = lo; s < hi; ++s) {
                const float x = X[s] - cx, y = Y[s] - cy, z = Z[s] - cz;
                const float d2 = x * x + y * y + z * z;
                const float k = d2 < R2 ? R / std::sqrt(std::max(d2, kTiny)) : 1.0f;
                const bool radial = (maybe[s - lo] & (fast[s - lo] ^ 1)) != 0;
                X[s] = QX[s - lo] = radial ? x * k + cx : X[s];
                Y[s] = QY[s - lo] = radial ? y * k + cy : Y[s];
                Z[s] = QZ[s - lo] = radial ? z * k + cz : Z[s];
            }
        }
        if (anyFast != 0) {
            for (std::size_t s = lo; s < hi; ++s) {
                float nx = X[s] - cx, ny = Y[s] - cy, nz = Z[s] - cz;
                pushOutAlongPath(nx, ny, nz, PX[s] - ox, PY[s] - oy, PZ[s] - oz, R);
                const bool path = (maybe[s - lo] & fast[s - lo]) != 0;
                X[s] = QX[s - lo] = path ? nx + cx : X[s];
                Y[s] = QY[s - lo] = path ? ny + cy : Y[s];
                Z[s] = QZ[s - lo] = path ? nz + cz : Z[s];
            }
        }
    }
}

// Contact for nodes already one segment from their parents (XP/YP/ZP): a node inside the sphere (centre,
// radius R) goes to its contact circle (sphereContact), choosing the point nearest where it was at the step's
// start (PX/PY/PZ) relative to the sphere then (anchorCentre: the sphere moved from there). A level of a block
// with no node inside skips the arithmetic (square roots and divisions) and is left exactly as it was.
inline void contactLevelInside(float* __restrict X, float* __restrict Y, float* __restrict Z,
                               const float* __restrict XP, const float* __restrict YP, const float* __restrict ZP,
                               const float* __restrict PX, const float* __restrict PY, const float* __restrict PZ,
                               std::size_t lo, std::size_t hi, float L, glm::vec3 anchorCentre, glm::vec3 centre,
                               float R);

inline void contactLevel(float* __restrict X, float* __restrict Y, float* __restrict Z, const float* __restrict XP,
                         const float* __restrict YP, const float* __restrict ZP, const float* __restrict PX,
                         const float* __restrict PY, const float* __restrict PZ, std::size_t lo, std::size_t hi,
                         float L, glm::vec3 anchorCentre, glm::vec3 centre, float R) {
    const float cx = centre.x, cy = centre.y, cz = centre.z, R2 = R * R;
    std::int32_t any = 0;
    for (std::size_t s = lo; s < hi; ++s) {
        const float x = X[s] - cx, y = Y[s] - cy, z = Z[s] - cz;
        any |= x * x + y * y + z * z < R2 ? 1 : 0;
    }
    if (any != 0) contactLevelInside(X, Y, Z, XP, YP, ZP, PX, PY, PZ, lo, hi, L, anchorCentre, centre, R);
}

// contactLevel's work once some node of the level is known to be inside.
inline void contactLevelInside(float* __restrict X, float* __restrict Y, float* __restrict Z,
                               const float* __restrict XP, const float* __restrict YP, const float* __restrict ZP,
                               const float* __restrict PX, const float* __restrict PY, const float* __restrict PZ,
                               std::size_t lo, std::size_t hi, float L, glm::vec3 anchorCentre, glm::vec3 centre,
                               float R) {
    const float cx = centre.x, cy = centre.y, cz = centre.z;
    const float ox = anchorCentre.x, oy = anchorCentre.y, oz = anchorCentre.z;
    std::int32_t radial[kMaxLanes];
    for (std::size_t s = lo; s < hi; ++s) {
        const float x0 = X[s] - cx, y0 = Y[s] - cy, z0 = Z[s] - cz;
        float x = x0, y = y0, z = z0;
        sphereContact(x, y, z, XP[s] - cx, YP[s] - cy, ZP[s] - cz, PX[s] - ox, PY[s] - oy, PZ[s] - oz, R, L,
                      radial[s - lo]);
        // Only a node the contact moved is written back: (X - c) + c is not always X in floats, and a node
        // resting a float's step off a block face (pushOutOfVoxels) must not be rounded back into the block.
        const bool moved = (x != x0) | (y != y0) | (z != z0);
        X[s] = moved ? x + cx : X[s];
        Y[s] = moved ? y + cy : Y[s];
        Z[s] = moved ? z + cz : Z[s];
    }
    std::int32_t anyRadial = 0;
    for (std::size_t l = 0; l < hi - lo; ++l) anyRadial |= radial[l];
    if (anyRadial == 0) return;
    for (std::size_t s = lo; s < hi; ++s) {
        float x = X[s] - cx, y = Y[s] - cy, z = Z[s] - cz;
        radialOut(x, y, z, R);
        const bool out = radial[s - lo] != 0;
        X[s] = out ? x + cx : X[s];
        Y[s] = out ? y + cy : Y[s];
        Z[s] = out ? z + cz : Z[s];
    }
}

// Follow the leader at one level: each node exactly L from its parent (the level above), then, when `host`,
// out of the host ball (moved from oldCentre to centre) onto its contact circle, so the length holds.
// P: the level's positions at the step's start (friction: see sphereContact).
template <bool host>
inline void ftlLevel(float* __restrict X, float* __restrict Y, float* __restrict Z, const float* __restrict XP,
                     const float* __restrict YP, const float* __restrict ZP, const float* __restrict PX,
                     const float* __restrict PY, const float* __restrict PZ, std::size_t lo, std::size_t hi, float L,
                     glm::vec3 oldCentre, glm::vec3 centre, float R) {
    [[maybe_unused]] const float cx = centre.x, cy = centre.y, cz = centre.z, R2 = R * R;
    [[maybe_unused]] std::int32_t inside[kMaxLanes]; // kept apart from the loop: a reduction in it stops vectorising
    for (std::size_t s = lo; s < hi; ++s) {
        const float dx = X[s] - XP[s], dy = Y[s] - YP[s], dz = Z[s] - ZP[s];
        const float k = L / std::sqrt(std::max(dx * dx + dy * dy + dz * dz, kTiny));
        const float x = XP[s] + dx * k, y = YP[s] + dy * k, z = ZP[s] + dz * k;
        X[s] = x, Y[s] = y, Z[s] = z;
        if constexpr (host) {
            const float rx = x - cx, ry = y - cy, rz = z - cz;
            inside[s - lo] = rx * rx + ry * ry + rz * rz < R2 ? 1 : 0;
        }
    }
    if constexpr (host) {
        std::int32_t any = 0;
        for (std::size_t l = 0; l < hi - lo; ++l) any |= inside[l];
        if (any != 0) contactLevelInside(X, Y, Z, XP, YP, ZP, PX, PY, PZ, lo, hi, L, oldCentre, centre, R);
    }
}

// One Gauss-Seidel projection of the segment between a parent level A and a child level B, equal masses
// (the root, parentFixed, does not move): both ends move along the segment so its length becomes L.
inline void pbdLevel(float* __restrict AX, float* __restrict AY, float* __restrict AZ, float* __restrict BX,
                     float* __restrict BY, float* __restrict BZ, std::size_t lo, std::size_t hi, float L,
                     bool parentFixed) {
    const float wa = parentFixed ? 0.0f : 0.5f, wb = parentFixed ? 1.0f : 0.5f; // w / (w_a + w_b)
    for (std::size_t s = lo; s < hi; ++s) {
        const float dx = BX[s] - AX[s], dy = BY[s] - AY[s], dz = BZ[s] - AZ[s];
        const float len = std::sqrt(std::max(dx * dx + dy * dy + dz * dz, kTiny));
        const float c = (len - L) / len; // the share of d that is stretch
        AX[s] += wa * c * dx, AY[s] += wa * c * dy, AZ[s] += wa * c * dz;
        BX[s] -= wb * c * dx, BY[s] -= wb * c * dy, BZ[s] -= wb * c * dz;
    }
}

// Out of the host ball the nearest way (radially), for the position-based methods' collision pass.
inline void radialPushLevel(float* __restrict X, float* __restrict Y, float* __restrict Z, std::size_t lo,
                            std::size_t hi, glm::vec3 centre, float R) {
    const float cx = centre.x, cy = centre.y, cz = centre.z, R2 = R * R;
    for (std::size_t s = lo; s < hi; ++s) {
        const float x = X[s] - cx, y = Y[s] - cy, z = Z[s] - cz;
        const float d2 = x * x + y * y + z * z;
        const float scale = R / std::sqrt(std::max(d2, kTiny));
        const float out = d2 < R2 ? scale : 1.0f;
        X[s] = x * out + cx, Y[s] = y * out + cy, Z[s] = z * out + cz;
    }
}

// SHAKE for a block of strands: positions x = q - w (lambda_k e_k - lambda_{k+1} e_{k+1}) with the constraint
// directions e from the step's start (P), lambda found by Newton's method on |x_k - x_{k-1}|^2 = L^2, each
// Newton step a tridiagonal solve (Thomas algorithm) per strand, run for all strands of the block at once.
// Level pointers: X/Y/Z and PX/PY/PZ at level 0 (the root, index = strand), stride S between levels; Q is the
// block's predicted positions (level n at Q + n * 3 * B + axis * B), work holds 3 * N * B + B floats.
inline void shakeBlock(float* __restrict X, float* __restrict Y, float* __restrict Z, const float* __restrict PX,
                       const float* __restrict PY, const float* __restrict PZ, const float* __restrict Q,
                       float* __restrict work, std::size_t S, std::size_t N, std::size_t lo, std::size_t hi,
                       std::size_t B, float L, int iterations) {
    const std::size_t w = hi - lo;
    float* const lam = work;            // lambda_k, k = 1..N-1 (index k * B + lane)
    float* const cp = work + N * B;     // Thomas c'
    float* const dp = work + 2 * N * B; // Thomas d', then the update
    float* const ok = work + 3 * N * B; // per lane: 1 while every segment's Newton direction is usable
    for (std::size_t k = 0; k < N; ++k)
        for (std::size_t l = 0; l < w; ++l) lam[k * B + l] = 0.0f;
    for (std::size_t l = 0; l < w; ++l) ok[l] = 1.0f;
    const auto q = [&](std::size_t n, std::size_t axis) { return Q + (n * 3 + axis) * B; };
    // x_k from lambda (the root stays where it was placed).
    const auto place = [&] {
        for (std::size_t k = 1; k < N; ++k) {
            const std::size_t o = k * S, op = o - S;
            const float* __restrict lk = lam + k * B;
            const float* __restrict lk1 = lam + (k + 1 < N ? (k + 1) * B : 0);
            const bool tip = k + 1 == N;
            const float* qx = q(k, 0);
            const float* qy = q(k, 1);
            const float* qz = q(k, 2);
            for (std::size_t s = lo; s < hi; ++s) {
                const std::size_t l = s - lo;
                const float ex = PX[o + s] - PX[op + s], ey = PY[o + s] - PY[op + s], ez = PZ[o + s] - PZ[op + s];
                float fx = lk[l] * ex, fy = lk[l] * ey, fz = lk[l] * ez;
                if (!tip) {
                    const std::size_t on = o + S;
                    const float nx = PX[on + s] - PX[o + s], ny = PY[on + s] - PY[o + s], nz = PZ[on + s] - PZ[o + s];
                    fx -= lk1[l] * nx, fy -= lk1[l] * ny, fz -= lk1[l] * nz;
                }
                X[o + s] = qx[l] - fx, Y[o + s] = qy[l] - fy, Z[o + s] = qz[l] - fz;
            }
        }
    };
    for (int it = 0; it < iterations; ++it) {
        place();
        // Forward sweep: row k (segment k) has sub (k-1), diag, super (k+1).
        for (std::size_t k = 1; k < N; ++k) {
            const std::size_t o = k * S, op = o - S;
            const bool first = k == 1, tip = k + 1 == N;
            float* __restrict cpk = cp + k * B;
            float* __restrict dpk = dp + k * B;
            const float* __restrict cpPrev = cp + (k - 1) * B;
            const float* __restrict dpPrev = dp + (k - 1) * B;
            for (std::size_t s = lo; s < hi; ++s) {
                const std::size_t l = s - lo;
                const float ex = X[o + s] - X[op + s], ey = Y[o + s] - Y[op + s], ez = Z[o + s] - Z[op + s];
                const float F = ex * ex + ey * ey + ez * ez - L * L;
                const float nx = PX[o + s] - PX[op + s], ny = PY[o + s] - PY[op + s], nz = PZ[o + s] - PZ[op + s];
                const float diag = -2.0f * (first ? 1.0f : 2.0f) * (ex * nx + ey * ny + ez * nz);
                float sup = 0.0f, sub = 0.0f;
                if (!tip) {
                    const std::size_t on = o + S;
                    const float ax = PX[on + s] - PX[o + s], ay = PY[on + s] - PY[o + s], az = PZ[on + s] - PZ[o + s];
                    sup = 2.0f * (ex * ax + ey * ay + ez * az);
                }
                if (!first) {
                    const std::size_t opp = op - S;
                    const float bx = PX[op + s] - PX[opp + s], by = PY[op + s] - PY[opp + s],
                                bz = PZ[op + s] - PZ[opp + s];
                    sub = 2.0f * (ex * bx + ey * by + ez * bz);
                }
                const float cPrev = first ? 0.0f : cpPrev[l], dPrev = first ? 0.0f : dpPrev[l];
                float m = diag - sub * cPrev;
                // SHAKE moves a node along the segment's direction at the step's start; once the segment has
                // turned more than 60 degrees in the step (a whipping tip), that direction can no longer
                // restore its length and Newton's method diverges. Such a strand keeps its prediction and
                // the follow-the-leader pass after SHAKE gives it its lengths.
                const float en = ex * nx + ey * ny + ez * nz;
                const bool turned =
                    !(en > 0.0f) | (4.0f * en * en < (ex * ex + ey * ey + ez * ez) * (nx * nx + ny * ny + nz * nz));
                ok[l] = turned ? 0.0f : ok[l];
                m = std::abs(m) > kTiny ? m : -kTiny;
                const float inv = 1.0f / m;
                cpk[l] = sup * inv;
                dpk[l] = (-F - sub * dPrev) * inv;
            }
        }
        // Back substitution, lambda += delta.
        for (std::size_t k = N - 1; k >= 1; --k) {
            float* __restrict dpk = dp + k * B;
            const float* __restrict cpk = cp + k * B;
            float* __restrict lk = lam + k * B;
            if (k + 1 < N) {
                const float* __restrict dNext = dp + (k + 1) * B;
                for (std::size_t l = 0; l < w; ++l) dpk[l] -= cpk[l] * dNext[l];
            }
            for (std::size_t l = 0; l < w; ++l) lk[l] += dpk[l];
        }
    }
    for (std::size_t k = 1; k < N; ++k)
        for (std::size_t l = 0; l < w; ++l) lam[k * B + l] *= ok[l];
    place();
}

// Follow-the-leader moves only the child, so nothing slows the parent down and a chain whips its tip
// (energy appears from nowhere). As in Mueller et al.'s "dynamic FTL", the parent's velocity gets back a share
// of the correction its child received, c_i = -s d_{i+1}: kept apart from the history (prev stays the true last
// position, which the renderer interpolates from) and added to the next Verlet displacement. X/Y/Z: the
// child's level; PX/PY/PZ: the parent's (its final positions this substep).
inline void correctParentVelocity(float* __restrict CX, float* __restrict CY, float* __restrict CZ,
                                  const float* __restrict X, const float* __restrict Y, const float* __restrict Z,
                                  const float* __restrict QX, const float* __restrict QY, const float* __restrict QZ,
                                  std::size_t lo, std::size_t hi, float share, const float* __restrict PX,
                                  const float* __restrict PY, const float* __restrict PZ, glm::vec3 centre, float R) {
    // A parent lying on its ball (within 0.1 mm of the surface) is held by friction: its child's pull does not
    // drag it along the surface (without this, hair draped over the top creeps for seconds after the host
    // stops). R < 0: no host collider.
    const float limit = R < 0.0f ? -1.0f : (R + 1e-4f) * (R + 1e-4f);
    const float cx = centre.x, cy = centre.y, cz = centre.z;
    for (std::size_t s = lo; s < hi; ++s) {
        const float dx = PX[s] - cx, dy = PY[s] - cy, dz = PZ[s] - cz;
        const float k = dx * dx + dy * dy + dz * dz < limit ? 0.0f : share;
        CX[s] = k * (QX[s - lo] - X[s]);
        CY[s] = k * (QY[s - lo] - Y[s]);
        CZ[s] = k * (QZ[s - lo] - Z[s]);
    }
}

} // namespace physics::kernels
