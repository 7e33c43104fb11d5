#pragma once
// A hexahedral ball for the Hertz tests: the cube [-1, 1]^3 (n^3 elements, graded towards the
// z axis and towards z = -1 so that the bottom pole, where contact happens, is finest) mapped
// onto the ball of radius R by p -> R p |p|_inf / |p|_2 (cube faces go to the sphere, the bottom
// face centre to the pole (0, 0, -R)). Centre at the origin.
#include <cmath>

#include "mesh/mesh.hpp"

namespace fem::test {

inline Mesh ball_hex8(double R, int n, double beta_axis, double beta_pole, const char* part = "ball") {
    Mesh m = box_hex8(2.0, 2.0, 2.0, n, n, n, part);
    for (auto& p : m.nodes) {
        Vec3 q = p - Vec3(1, 1, 1);
        // Grading: odd cubic in x, y (slope beta_axis at the axis), quadratic in z (slope beta_pole at -1).
        for (int d = 0; d < 2; ++d) q[d] = beta_axis * q[d] + (1 - beta_axis) * q[d] * q[d] * q[d];
        q.z() = -1 + (q.z() + 1) * (beta_pole + (1 - beta_pole) * (q.z() + 1) / 2);
        const double l2 = q.norm();
        p = l2 > 0 ? Vec3(R * q * (q.cwiseAbs().maxCoeff() / l2)) : Vec3::Zero();
    }
    return m;
}

}  // namespace fem::test
