#include "element/plane_stress.hpp"

#include <array>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace fem::plane {
namespace {

void require_quad(ElementShape shape) {
    if (shape != ElementShape::Quad4 && shape != ElementShape::Quad8)
        throw InputError("plane-stress element: shape " + std::string(to_string(shape)) +
                         " is not supported (quad4 or quad8)");
}

// Gauss-Legendre points and weights on [-1, 1].
struct Rule { std::array<double, 3> x, w; int n; };
Rule gauss(int n) {
    if (n == 2) {
        const double a = 1.0 / std::sqrt(3.0);
        return {{-a, a, 0.0}, {1.0, 1.0, 0.0}, 2};
    }
    const double a = std::sqrt(0.6);
    return {{-a, 0.0, a}, {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0}, 3};
}

// Parametric coordinates of the nodes: corners, then mid-sides 01, 12, 23, 30.
constexpr double kXi[8] = {-1, 1, 1, -1, 0, 1, 0, -1};
constexpr double kEta[8] = {-1, -1, 1, 1, -1, 0, 1, 0};

}  // namespace

Eigen::Matrix3d plane_stress_matrix(double E, double nu) {
    if (!(E > 0)) throw InputError("plane-stress material: Young's modulus must be > 0, got " + std::to_string(E));
    if (!(nu > -1.0 && nu < 0.5))
        throw InputError("plane-stress material: Poisson's ratio must lie in (-1, 0.5), got " + std::to_string(nu));
    Eigen::Matrix3d D;
    D << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
    return D * (E / (1 - nu * nu));
}

int gauss_order(ElementShape shape) {
    require_quad(shape);
    return shape == ElementShape::Quad4 ? 2 : 3;
}

void shape_functions(ElementShape shape, double xi, double eta, Eigen::VectorXd& N, Eigen::MatrixXd& dN) {
    require_quad(shape);
    const int n = node_count(shape);
    N.resize(n);
    dN.resize(n, 2);
    if (shape == ElementShape::Quad4) {
        for (int i = 0; i < 4; ++i) {
            const double a = kXi[i], b = kEta[i];
            N(i) = 0.25 * (1 + a * xi) * (1 + b * eta);
            dN(i, 0) = 0.25 * a * (1 + b * eta);
            dN(i, 1) = 0.25 * b * (1 + a * xi);
        }
        return;
    }
    // 8-node serendipity: corners N = (1 + a xi)(1 + b eta)(a xi + b eta - 1) / 4, mid-sides
    // N = (1 - xi^2)(1 + b eta) / 2 (a = 0) or (1 + a xi)(1 - eta^2) / 2 (b = 0).
    for (int i = 0; i < 8; ++i) {
        const double a = kXi[i], b = kEta[i];
        if (i < 4) {
            N(i) = 0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1);
            dN(i, 0) = 0.25 * a * (1 + b * eta) * (2 * a * xi + b * eta);
            dN(i, 1) = 0.25 * b * (1 + a * xi) * (a * xi + 2 * b * eta);
        } else if (a == 0) {
            N(i) = 0.5 * (1 - xi * xi) * (1 + b * eta);
            dN(i, 0) = -xi * (1 + b * eta);
            dN(i, 1) = 0.5 * b * (1 - xi * xi);
        } else {
            N(i) = 0.5 * (1 + a * xi) * (1 - eta * eta);
            dN(i, 0) = 0.5 * a * (1 - eta * eta);
            dN(i, 1) = -eta * (1 + a * xi);
        }
    }
}

double strain_displacement(ElementShape shape, std::span<const Vec3> x, double xi, double eta, Eigen::MatrixXd& B) {
    require_quad(shape);
    const int n = node_count(shape);
    if (static_cast<int>(x.size()) != n)
        throw InputError("plane-stress element: " + std::string(to_string(shape)) + " needs " + std::to_string(n) +
                         " nodes, got " + std::to_string(x.size()));
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    shape_functions(shape, xi, eta, N, dN);
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();  // J(i, j) = d x_j / d xi_i
    for (int k = 0; k < n; ++k) {
        J(0, 0) += dN(k, 0) * x[k].x();
        J(0, 1) += dN(k, 0) * x[k].y();
        J(1, 0) += dN(k, 1) * x[k].x();
        J(1, 1) += dN(k, 1) * x[k].y();
    }
    const double det = J.determinant();
    if (!(det > 0))
        throw InputError("plane-stress element: inverted or degenerate " + std::string(to_string(shape)) +
                         " (det J = " + std::to_string(det) + " at xi = " + std::to_string(xi) +
                         ", eta = " + std::to_string(eta) + "; nodes must run counter-clockwise)");
    const Eigen::MatrixXd dNdx = dN * J.inverse().transpose();  // n x 2: dN/dx, dN/dy
    B.setZero(3, 2 * n);
    for (int k = 0; k < n; ++k) {
        B(0, 2 * k) = dNdx(k, 0);
        B(1, 2 * k + 1) = dNdx(k, 1);
        B(2, 2 * k) = dNdx(k, 1);
        B(2, 2 * k + 1) = dNdx(k, 0);
    }
    return det;
}

Eigen::MatrixXd stiffness(ElementShape shape, std::span<const Vec3> x, double E, double nu, double t) {
    require_quad(shape);
    if (!(t > 0)) throw InputError("plane-stress element: thickness must be > 0, got " + std::to_string(t));
    const Eigen::Matrix3d D = plane_stress_matrix(E, nu);
    const int n = node_count(shape);
    const Rule g = gauss(gauss_order(shape));
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(2 * n, 2 * n), B;
    for (int i = 0; i < g.n; ++i)
        for (int j = 0; j < g.n; ++j) {
            const double det = strain_displacement(shape, x, g.x[i], g.x[j], B);
            K.noalias() += (t * det * g.w[i] * g.w[j]) * (B.transpose() * D * B);
        }
    return 0.5 * (K + K.transpose());  // symmetric to round-off
}

double area(ElementShape shape, std::span<const Vec3> x) {
    const Rule g = gauss(gauss_order(shape));
    Eigen::MatrixXd B;
    double a = 0;
    for (int i = 0; i < g.n; ++i)
        for (int j = 0; j < g.n; ++j) a += strain_displacement(shape, x, g.x[i], g.x[j], B) * g.w[i] * g.w[j];
    return a;
}

}  // namespace fem::plane
