#include "element/solid_elements.hpp"

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/error.hpp"

namespace fem::solid {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;

// Natural coordinates of the hex8 corners in the library's order (bottom face then top face).
constexpr std::array<std::array<double, 3>, 8> kHexCorner = {{
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}};

// Tet10 mid-edge nodes 4..9 and the corners of their edges (Gmsh order, see the header).
constexpr std::array<std::array<int, 2>, 6> kTetEdge = {{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}}};

// Shape functions and natural derivatives (rows: d/dxi, d/deta, d/dzeta).
template <int N>
struct ShapeEval {
    Eigen::Matrix<double, N, 1> n;
    Eigen::Matrix<double, 3, N> dn;
};

ShapeEval<8> hex8_shape(double r, double s, double t) {
    ShapeEval<8> e;
    for (int a = 0; a < 8; ++a) {
        const double ra = kHexCorner[a][0], sa = kHexCorner[a][1], ta = kHexCorner[a][2];
        const double fr = 1 + r * ra, fs = 1 + s * sa, ft = 1 + t * ta;
        e.n(a) = fr * fs * ft / 8;
        e.dn(0, a) = ra * fs * ft / 8;
        e.dn(1, a) = fr * sa * ft / 8;
        e.dn(2, a) = fr * fs * ta / 8;
    }
    return e;
}

// Tet10 in volume coordinates L0 = 1 - r - s - t, L1 = r, L2 = s, L3 = t: corners L(2L - 1),
// mid-edge 4 Li Lj.
ShapeEval<10> tet10_shape(double r, double s, double t) {
    const double L[4] = {1 - r - s - t, r, s, t};
    // dL/d(r,s,t) for each L.
    const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    ShapeEval<10> e;
    for (int a = 0; a < 4; ++a) {
        e.n(a) = L[a] * (2 * L[a] - 1);
        for (int d = 0; d < 3; ++d) e.dn(d, a) = (4 * L[a] - 1) * dL[a][d];
    }
    for (int k = 0; k < 6; ++k) {
        const int i = kTetEdge[k][0], j = kTetEdge[k][1];
        e.n(4 + k) = 4 * L[i] * L[j];
        for (int d = 0; d < 3; ++d) e.dn(d, 4 + k) = 4 * (dL[i][d] * L[j] + L[i] * dL[j][d]);
    }
    return e;
}

template <int N>
Eigen::Matrix<double, 3, N> coordinates(std::span<const Vec3> x, const char* what) {
    if (static_cast<int>(x.size()) != N)
        throw InputError(std::string(what) + " needs " + std::to_string(N) + " node coordinates, got " +
                         std::to_string(x.size()));
    Eigen::Matrix<double, 3, N> X;
    for (int a = 0; a < N; ++a) X.col(a) = x[a];
    return X;
}

// Physical derivatives dN/dx (3 x N) and det J at one point; throws for det J <= 0.
template <int N>
double physical_derivatives(const Eigen::Matrix<double, 3, N>& X, const Eigen::Matrix<double, 3, N>& dn,
                            Eigen::Matrix<double, 3, N>& dndx, const char* what) {
    const Mat3 J = dn * X.transpose();  // J(i, j) = d x_j / d xi_i
    const double det = J.determinant();
    if (!(det > 0.0))
        throw InputError(std::string(what) + " has a non-positive Jacobian (" + std::to_string(det) +
                         ") at an integration point: the element is inverted or badly distorted");
    dndx = J.inverse() * dn;
    return det;
}

// Strain-displacement matrix B (6 x 3N) from the physical derivatives, Voigt order of D.
template <int N>
Eigen::Matrix<double, 6, 3 * N> strain_matrix(const Eigen::Matrix<double, 3, N>& g) {
    Eigen::Matrix<double, 6, 3 * N> B = Eigen::Matrix<double, 6, 3 * N>::Zero();
    for (int a = 0; a < N; ++a) {
        const double bx = g(0, a), by = g(1, a), bz = g(2, a);
        B(0, 3 * a) = bx;
        B(1, 3 * a + 1) = by;
        B(2, 3 * a + 2) = bz;
        B(3, 3 * a) = by, B(3, 3 * a + 1) = bx;
        B(4, 3 * a + 1) = bz, B(4, 3 * a + 2) = by;
        B(5, 3 * a) = bz, B(5, 3 * a + 2) = bx;
    }
    return B;
}

// Expands a scalar mass matrix m (N x N, int rho Na Nb) to the 3N x 3N matrix of three components.
Eigen::MatrixXd expand3(const Eigen::MatrixXd& m) {
    const int n = static_cast<int>(m.rows());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            for (int d = 0; d < 3; ++d) M(3 * a + d, 3 * b + d) = m(a, b);
    return M;
}

const double kGauss2 = 1.0 / std::sqrt(3.0);

// HRZ lumping (Hinton, Rock & Zienkiewicz 1976): keep the diagonal of a consistent scalar mass,
// scaled to the element mass (positive where quadratic elements' row sums are not).
Eigen::MatrixXd hrz_lumped(const Eigen::MatrixXd& m) {
    const Eigen::VectorXd d = m.diagonal() * (m.sum() / m.diagonal().sum());
    return d.asDiagonal();
}

// 4-point tet rule (degree 2): points at (a, b, b) permutations, a = (5 + 3 sqrt 5) / 20,
// b = (5 - sqrt 5) / 20, weight 1/24 each (reference volume 1/6).
struct TetPoint { double r, s, t, w; };
std::array<TetPoint, 4> tet_rule4() {
    const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
    return {{{b, b, b, 1.0 / 24}, {a, b, b, 1.0 / 24}, {b, a, b, 1.0 / 24}, {b, b, a, 1.0 / 24}}};
}

// Conical-product (collapsed cube) rule on the reference tet, 4 Gauss-Legendre points per direction:
// (u, v, w) in [0,1]^3 -> r = u, s = v (1 - u), t = w (1 - u)(1 - v) with Jacobian (1 - u)^2 (1 - v);
// exact for polynomials up to degree 5 in (r, s, t) (u carries degree p + 2 <= 7).
std::vector<TetPoint> tet_rule_conical() {
    const double g[4] = {-std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(6.0 / 5)), -std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(6.0 / 5)),
                         std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(6.0 / 5)), std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(6.0 / 5))};
    const double wo = (18.0 - std::sqrt(30.0)) / 36, wi = (18.0 + std::sqrt(30.0)) / 36;
    const double w[4] = {wo, wi, wi, wo};
    std::vector<TetPoint> pts;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
                const double u = (1 + g[i]) / 2, v = (1 + g[j]) / 2, ww = (1 + g[k]) / 2;
                const double weight = w[i] * w[j] * w[k] / 8 * (1 - u) * (1 - u) * (1 - v);
                pts.push_back({u, v * (1 - u), ww * (1 - u) * (1 - v), weight});
            }
    return pts;
}

}  // namespace

Mat6 elasticity_matrix(const ElasticMaterial& m) {
    const double lambda = m.lame_lambda(), mu = m.shear_modulus();
    Mat6 D = Mat6::Zero();
    D.topLeftCorner<3, 3>().setConstant(lambda);
    for (int i = 0; i < 3; ++i) D(i, i) = lambda + 2 * mu, D(3 + i, 3 + i) = mu;
    return D;
}

namespace {

// The hex8 stiffness before condensation: Kuu (24 x 24, the trilinear brick), and with the nine
// bubble amplitudes a (bubble k = 0, 1, 2 times component x, y, z: column 3k + d) Kua (24 x 9) and
// Kaa (9 x 9); 2x2x2 Gauss.
struct Hex8Blocks {
    Eigen::Matrix<double, 24, 24> uu = Eigen::Matrix<double, 24, 24>::Zero();
    Eigen::Matrix<double, 24, 9> ua = Eigen::Matrix<double, 24, 9>::Zero();
    Eigen::Matrix<double, 9, 9> aa = Eigen::Matrix<double, 9, 9>::Zero();
};

Hex8Blocks hex8_blocks(const Eigen::Matrix<double, 3, 8>& X, const ElasticMaterial& m, bool incompatible_modes) {
    const Mat6 D = elasticity_matrix(m);
    Hex8Blocks k;
    // Centre Jacobian for the incompatible modes (Taylor, Beresford & Wilson 1976): their gradients
    // are mapped with J0 and scaled by det J0 / det J so that a constant strain state is reproduced.
    Eigen::Matrix<double, 3, 8> g0;
    const ShapeEval<8> c = hex8_shape(0, 0, 0);
    const double det0 = physical_derivatives<8>(X, c.dn, g0, "hex8 element");
    const Mat3 J0inv = (c.dn * X.transpose()).inverse();
    for (int i = 0; i < 8; ++i) {
        const double r = kHexCorner[i][0] * kGauss2, s = kHexCorner[i][1] * kGauss2, t = kHexCorner[i][2] * kGauss2;
        const ShapeEval<8> e = hex8_shape(r, s, t);
        Eigen::Matrix<double, 3, 8> g;
        const double det = physical_derivatives<8>(X, e.dn, g, "hex8 element");
        const Eigen::Matrix<double, 6, 24> B = strain_matrix<8>(g);
        k.uu.noalias() += B.transpose() * D * B * det;  // Gauss weights are 1
        if (!incompatible_modes) continue;
        // Bubble modes P_k = 1 - xi_k^2: natural gradient -2 xi_k along direction k only.
        Eigen::Matrix<double, 3, 3> dp = Eigen::Matrix3d::Zero();
        dp(0, 0) = -2 * r, dp(1, 1) = -2 * s, dp(2, 2) = -2 * t;
        const Eigen::Matrix<double, 3, 3> gp = J0inv * dp * (det0 / det);
        const Eigen::Matrix<double, 6, 9> Ba = strain_matrix<3>(gp);
        k.ua.noalias() += B.transpose() * D * Ba * det;
        k.aa.noalias() += Ba.transpose() * D * Ba * det;
    }
    return k;
}

}  // namespace

Eigen::MatrixXd hex8_stiffness(std::span<const Vec3> x, const ElasticMaterial& m, bool incompatible_modes) {
    Hex8Blocks k = hex8_blocks(coordinates<8>(x, "hex8 element"), m, incompatible_modes);
    if (incompatible_modes) k.uu -= k.ua * k.aa.ldlt().solve(k.ua.transpose());
    return Eigen::MatrixXd(0.5 * (k.uu + k.uu.transpose()));
}

Hex8IncompatibleDofs hex8_incompatible_dofs(std::span<const Vec3> x, const ElasticMaterial& m) {
    const auto X = coordinates<8>(x, "hex8 element");
    const Hex8Blocks k = hex8_blocks(X, m, true);
    Hex8IncompatibleDofs out;
    out.stiffness.resize(33, 33);
    out.stiffness << k.uu, k.ua, k.ua.transpose(), k.aa;
    out.stiffness = 0.5 * (out.stiffness + out.stiffness.transpose());
    // The mass of the same displacement field: the eight trilinear functions and the three bubbles
    // 1 - xi_k^2 (each carrying three components), with the stiffness's 2x2x2 rule. The rule is exact
    // for the trilinear part of a parallelepiped but not for the bubbles (degree 4 along xi_k): there
    // each bubble is 2/3 at every point, which gives it 4/9 of the element's mass where the exact
    // integral gives 8/15. CalculiX builds its C3D8I mass so (shape8humass.f); we follow it.
    Eigen::MatrixXd mm = Eigen::MatrixXd::Zero(11, 11);
    for (int i = 0; i < 8; ++i) {
        const double r = kHexCorner[i][0] * kGauss2, s = kHexCorner[i][1] * kGauss2, t = kHexCorner[i][2] * kGauss2;
        const ShapeEval<8> e = hex8_shape(r, s, t);
        Eigen::Matrix<double, 3, 8> g;
        const double det = physical_derivatives<8>(X, e.dn, g, "hex8 element");
        Eigen::Matrix<double, 11, 1> n;
        n << e.n, 1 - r * r, 1 - s * s, 1 - t * t;
        mm.noalias() += m.density * det * n * n.transpose();
    }
    out.mass = expand3(mm);
    return out;
}

Eigen::MatrixXd hex8_mass(std::span<const Vec3> x, double density, MassKind kind) {
    const auto X = coordinates<8>(x, "hex8 element");
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(8, 8);
    for (int i = 0; i < 8; ++i) {
        const ShapeEval<8> e = hex8_shape(kHexCorner[i][0] * kGauss2, kHexCorner[i][1] * kGauss2, kHexCorner[i][2] * kGauss2);
        Eigen::Matrix<double, 3, 8> g;
        const double det = physical_derivatives<8>(X, e.dn, g, "hex8 element");
        m.noalias() += density * det * e.n * e.n.transpose();
    }
    if (kind == MassKind::Lumped) {
        // Row sums: positive for the trilinear brick (all N_a >= 0).
        const Eigen::VectorXd rows = m.rowwise().sum();
        m = rows.asDiagonal();
    }
    return expand3(m);
}

Eigen::MatrixXd tet10_stiffness(std::span<const Vec3> x, const ElasticMaterial& m) {
    const auto X = coordinates<10>(x, "tet10 element");
    const Mat6 D = elasticity_matrix(m);
    Eigen::Matrix<double, 30, 30> K = Eigen::Matrix<double, 30, 30>::Zero();
    for (const TetPoint& p : tet_rule4()) {
        const ShapeEval<10> e = tet10_shape(p.r, p.s, p.t);
        Eigen::Matrix<double, 3, 10> g;
        const double det = physical_derivatives<10>(X, e.dn, g, "tet10 element");
        const Eigen::Matrix<double, 6, 30> B = strain_matrix<10>(g);
        K.noalias() += B.transpose() * (D * B) * (det * p.w);
    }
    return Eigen::MatrixXd(0.5 * (K + K.transpose()));
}

Eigen::MatrixXd tet10_mass(std::span<const Vec3> x, double density, MassKind kind, Tet10MassRule rule) {
    const auto X = coordinates<10>(x, "tet10 element");
    static const std::vector<TetPoint> conical = tet_rule_conical();
    const auto four = tet_rule4();
    const std::span<const TetPoint> pts = rule == Tet10MassRule::Exact ? std::span<const TetPoint>(conical)
                                                                        : std::span<const TetPoint>(four);
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(10, 10);
    for (const TetPoint& p : pts) {
        const ShapeEval<10> e = tet10_shape(p.r, p.s, p.t);
        Eigen::Matrix<double, 3, 10> g;
        const double det = physical_derivatives<10>(X, e.dn, g, "tet10 element");
        m.noalias() += (density * det * p.w) * e.n * e.n.transpose();
    }
    if (kind == MassKind::Lumped) m = hrz_lumped(m);
    return expand3(m);
}

namespace {

// Hex20 natural node coordinates: the corners, then the mid-edge nodes (ElementShape::Hex20 order).
constexpr std::array<std::array<double, 3>, 20> kHex20Node = {{
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1},
    {0, -1, -1},  {1, 0, -1},  {0, 1, -1}, {-1, 0, -1}, {0, -1, 1},  {1, 0, 1},  {0, 1, 1}, {-1, 0, 1},
    {-1, -1, 0},  {1, -1, 0},  {1, 1, 0},  {-1, 1, 0}}};

// Serendipity shape functions: corners (1 + r ra)(1 + s sa)(1 + t ta)(r ra + s sa + t ta - 2) / 8;
// a mid-edge node with ra = 0: (1 - r^2)(1 + s sa)(1 + t ta) / 4 (likewise for sa = 0, ta = 0).
ShapeEval<20> hex20_shape(double r, double s, double t) {
    ShapeEval<20> e;
    const double q[3] = {r, s, t};
    for (int a = 0; a < 20; ++a) {
        const auto& c = kHex20Node[a];
        double f[3], df[3];  // the three linear factors (1 + q c) and their derivatives
        for (int d = 0; d < 3; ++d) f[d] = 1 + q[d] * c[d], df[d] = c[d];
        if (a < 8) {
            const double sum = r * c[0] + s * c[1] + t * c[2] - 2;
            e.n(a) = f[0] * f[1] * f[2] * sum / 8;
            for (int d = 0; d < 3; ++d) {
                const double others = f[(d + 1) % 3] * f[(d + 2) % 3];
                e.dn(d, a) = c[d] * others * (sum + f[d]) / 8;
            }
        } else {
            int z = 0;  // the direction along the edge (coordinate 0)
            while (c[z] != 0) ++z;
            f[z] = 1 - q[z] * q[z], df[z] = -2 * q[z];
            e.n(a) = f[0] * f[1] * f[2] / 4;
            for (int d = 0; d < 3; ++d) e.dn(d, a) = df[d] * f[(d + 1) % 3] * f[(d + 2) % 3] / 4;
        }
    }
    return e;
}

// Gauss-Legendre points and weights on [-1, 1]: 2 (reduced) or 3 (full) per direction.
struct Gauss1D { std::vector<double> x, w; };
Gauss1D gauss_1d(bool reduced) {
    if (reduced) return {{-kGauss2, kGauss2}, {1, 1}};
    const double g = std::sqrt(0.6);
    return {{-g, 0, g}, {5.0 / 9, 8.0 / 9, 5.0 / 9}};
}

// Calls f(shape functions, physical derivatives, det J x weight) at each point of the product rule.
template <class F>
void for_each_hex20_point(const Eigen::Matrix<double, 3, 20>& X, bool reduced, F f) {
    const Gauss1D g = gauss_1d(reduced);
    for (std::size_t i = 0; i < g.x.size(); ++i)
        for (std::size_t j = 0; j < g.x.size(); ++j)
            for (std::size_t k = 0; k < g.x.size(); ++k) {
                const ShapeEval<20> e = hex20_shape(g.x[i], g.x[j], g.x[k]);
                Eigen::Matrix<double, 3, 20> gr;
                const double det = physical_derivatives<20>(X, e.dn, gr, "hex20 element");
                f(e, gr, det * g.w[i] * g.w[j] * g.w[k]);
            }
}

}  // namespace

Eigen::MatrixXd hex20_stiffness(std::span<const Vec3> x, const ElasticMaterial& m, bool reduced) {
    const Mat6 D = elasticity_matrix(m);
    Eigen::Matrix<double, 60, 60> K = Eigen::Matrix<double, 60, 60>::Zero();
    for_each_hex20_point(coordinates<20>(x, "hex20 element"), reduced,
                         [&](const ShapeEval<20>&, const Eigen::Matrix<double, 3, 20>& gr, double dv) {
                             const Eigen::Matrix<double, 6, 60> B = strain_matrix<20>(gr);
                             K.noalias() += B.transpose() * (D * B) * dv;
                         });
    return Eigen::MatrixXd(0.5 * (K + K.transpose()));
}

Eigen::MatrixXd hex20_mass(std::span<const Vec3> x, double density, MassKind kind, bool reduced) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(20, 20);
    for_each_hex20_point(coordinates<20>(x, "hex20 element"), reduced,
                         [&](const ShapeEval<20>& e, const Eigen::Matrix<double, 3, 20>&, double dv) {
                             m.noalias() += (density * dv) * e.n * e.n.transpose();
                         });
    if (kind == MassKind::Lumped) m = hrz_lumped(m);  // corner row sums are negative, as for tet10
    return expand3(m);
}

Eigen::MatrixXd tet4_stiffness(std::span<const Vec3> x, const ElasticMaterial& m) {
    const auto X = coordinates<4>(x, "tet4 element");
    // Linear shape functions L0 = 1 - r - s - t, L1 = r, L2 = s, L3 = t: constant gradients.
    Eigen::Matrix<double, 3, 4> dn;
    dn << -1, 1, 0, 0, -1, 0, 1, 0, -1, 0, 0, 1;
    Eigen::Matrix<double, 3, 4> g;
    const double det = physical_derivatives<4>(X, dn, g, "tet4 element");
    const Eigen::Matrix<double, 6, 12> B = strain_matrix<4>(g);
    const Eigen::Matrix<double, 12, 12> K = B.transpose() * elasticity_matrix(m) * B * (det / 6);
    return Eigen::MatrixXd(0.5 * (K + K.transpose()));
}

Eigen::MatrixXd tet4_mass(std::span<const Vec3> x, double density, MassKind kind, Tet4MassRule rule) {
    const auto X = coordinates<4>(x, "tet4 element");
    const Mat3 J = (X.rightCols<3>().colwise() - X.col(0)).transpose();
    const double volume = J.determinant() / 6;
    if (!(volume > 0.0))
        throw InputError("tet4 element has a non-positive volume (" + std::to_string(volume) + "): it is inverted or flat");
    const double mass = density * volume;
    // int N_a N_b dV = V (1 + delta_ab) / 20 for linear shape functions.
    Eigen::MatrixXd m;
    if (kind == MassKind::Lumped) m = Eigen::MatrixXd::Identity(4, 4) * (mass / 4);
    else if (rule == Tet4MassRule::Centroid) m = Eigen::MatrixXd::Ones(4, 4) * (mass / 16);  // N_a = 1/4 at the centroid
    else m = (Eigen::MatrixXd::Ones(4, 4) + Eigen::MatrixXd::Identity(4, 4)) * (mass / 20);
    return expand3(m);
}

double hex8_volume(std::span<const Vec3> x) {
    return hex8_mass(x, 1.0, MassKind::Consistent).sum() / 3.0;
}

double tet10_volume(std::span<const Vec3> x) {
    return tet10_mass(x, 1.0, MassKind::Consistent).sum() / 3.0;
}

}  // namespace fem::solid
