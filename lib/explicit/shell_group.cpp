#include "explicit/shell_group.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Spectra/SymEigsSolver.h>
#include <fmt/format.h>

#include "core/eigen_instances.hpp"
#include "core/error.hpp"

namespace fem {

ShellGroup::ShellGroup(const Mesh& mesh, int block, const ElasticMaterial& material, const ShellOptions& options)
    : material_(material), section_(options) {
    const ElementBlock& b = mesh.blocks.at(block);
    if (b.shape != ElementShape::Quad4 && b.shape != ElementShape::Tri3)
        throw InputError(fmt::format("part '{}' (block {}) is {}, not a shell (quad4 or tri3)", b.part, block,
                                     to_string(b.shape)));
    part = b.part;
    this->block = block;
    section_.validate(fmt::format("part '{}'", part).c_str());
    consts_ = shellbt::Constants::from(material_, section_);
    triangles_ = b.shape == ElementShape::Tri3;
    const int n = b.size();
    conn_.resize(n);
    mass_.resize(n);
    ref_dt_.resize(n);
    for (int e = 0; e < n; ++e) {
        const auto c = b.element(e);
        conn_[e] = triangles_ ? std::array<int, 4>{c[0], c[1], c[2], c[2]} : std::array<int, 4>{c[0], c[1], c[2], c[3]};
        std::array<Vec3, 4> X;
        for (int a = 0; a < 4; ++a) X[a] = mesh.nodes.at(conn_[e][a]);
        const shellbt::Frame f = shellbt::make_frame(X);
        if (!(f.area > 0.0))
            throw InputError(fmt::format("part '{}' block {} {} element {}: degenerate element (zero area or a side "
                                         "of zero length)",
                                         part, block, to_string(b.shape), e));
        // A quadrilateral whose projected corners are not convex (inverted or bow-tie) has a node
        // with a non-positive tributary area in the one-point operators.
        if (!triangles_)
            for (int a = 0; a < 4; ++a) {
                const Vec3 e1 = X[(a + 1) % 4] - X[a], e0 = X[(a + 3) % 4] - X[a];
                if (!(e1.cross(e0).dot(f.E.col(2)) > 0.0))
                    throw InputError(fmt::format("part '{}' block {} quad4 element {}: not convex at its node {} "
                                                 "(mesh node {}): inverted or bow-tie element",
                                                 part, block, e, a, conn_[e][a]));
            }
        mass_[e] = shellbt::lumped_mass(consts_, X, triangles_);
        ref_dt_[e] = shellbt::critical_time_step(material_, X, triangles_);
    }
    mass_scale_.assign(n, 1.0);

    std::vector<char> used(mesh.node_count(), 0);
    for (const auto& c : conn_)
        for (int a : c) used[a] = 1;
    local_.assign(mesh.node_count(), -1);
    for (int i = 0; i < mesh.node_count(); ++i)
        if (used[i]) {
            local_[i] = static_cast<int>(nodes_.size());
            nodes_.push_back(i);
        }
    order_ = par::node_order(conn_);
    position_.resize(n);
    kconn_.resize(n);
    klocal_.resize(n);
    for (int k = 0; k < n; ++k) {
        const int e = order_[k];
        position_[e] = k;
        kconn_[k] = conn_[e];
        for (int a = 0; a < 4; ++a) klocal_[k][a] = local_[conn_[e][a]];
    }
    sqrt_mass_scale_.assign(n, 1.0);
    state_.assign(n, shellbt::State{});
    vm_sq_.assign(n, {0.0, 0.0, 0.0});
    const int nn = static_cast<int>(nodes_.size());
    X_.resize(nn);
    for (int k = 0; k < nn; ++k) X_[k] = mesh.nodes[nodes_[k]];
    x_prev_ = X_;
    R_prev_.assign(nn, Mat3::Identity());
    x_mid_.assign(nn, Vec3::Zero());
    du_.assign(nn, Vec3::Zero());
    dtheta_.assign(nn, Vec3::Zero());
    colouring_ = par::ChunkColouring::build(kconn_, mesh.node_count(), kChunk);
    partial_.resize(colouring_.chunk_count());
}

void ShellGroup::initialize(const NodalState& s) {
    for (std::size_t k = 0; k < nodes_.size(); ++k) {
        const int node = nodes_[k];
        x_prev_[k] = s.x[node];
        const int r = s.rot_index[node];
        R_prev_[k] = r >= 0 ? s.rotation[r] : Mat3::Identity();
    }
    std::fill(state_.begin(), state_.end(), shellbt::State{});
    for (auto& v : vm_sq_) v = {0.0, 0.0, 0.0};
    // Stability factor on the Table 2-1 steps (shell_group.hpp), with the masses of this run.
    double table = std::numeric_limits<double>::infinity();
    for (int e = 0; e < size(); ++e) table = std::min(table, ref_dt_[e] * std::sqrt(mass_scale_[e]));
    const double w = measure_omega_max();
    factor_ = w > 0.0 ? std::min(1.0, (2.0 / w) / table) : 1.0;
}

namespace {
// y = M^-1/2 K M^-1/2 x over the 6 DOFs of the group's nodes, K applied element by element with
// the kernel's exact linear operators on the reference frames (update_state + forces from a zero
// state: linear in the increments).
class ShellStiffnessOp {
public:
    using Scalar = double;
    ShellStiffnessOp(const shellbt::Constants& c, std::vector<shellbt::Frame> frames,
                     const std::vector<std::array<int, 4>>& local_conn, std::vector<double> inv_sqrt_mass)
        : c_(c), frames_(std::move(frames)), conn_(local_conn), w_(std::move(inv_sqrt_mass)) {}
    int rows() const { return static_cast<int>(w_.size()); }
    int cols() const { return rows(); }
    void perform_op(const double* x, double* y) const {
        std::fill(y, y + rows(), 0.0);
        std::array<Vec3, 4> du, dth;
        shellbt::Result r;
        for (std::size_t e = 0; e < conn_.size(); ++e) {
            const auto& cn = conn_[e];
            for (int a = 0; a < 4; ++a) {
                const int o = 6 * cn[a];
                du[a] = Vec3(x[o] * w_[o], x[o + 1] * w_[o + 1], x[o + 2] * w_[o + 2]);
                dth[a] = Vec3(x[o + 3] * w_[o + 3], x[o + 4] * w_[o + 4], x[o + 5] * w_[o + 5]);
            }
            shellbt::State st;
            shellbt::update_state(c_, frames_[e], du, dth, st);
            shellbt::forces(c_, frames_[e], st, r);
            for (int a = 0; a < 4; ++a) {
                const int o = 6 * cn[a];
                for (int d = 0; d < 3; ++d) {
                    y[o + d] += r.force[a][d] * w_[o + d];
                    y[o + 3 + d] += r.moment[a][d] * w_[o + 3 + d];
                }
            }
        }
    }

private:
    const shellbt::Constants& c_;
    std::vector<shellbt::Frame> frames_;
    const std::vector<std::array<int, 4>>& conn_;
    std::vector<double> w_;
};
}  // namespace

double ShellGroup::measure_omega_max() const {
    const int nn = static_cast<int>(nodes_.size());
    std::vector<double> m(6 * nn, 0.0);
    std::vector<shellbt::Frame> frames(size());
    std::vector<std::array<int, 4>> lconn(size());
    for (int e = 0; e < size(); ++e) {
        std::array<Vec3, 4> X;
        for (int a = 0; a < 4; ++a) {
            lconn[e][a] = local_[conn_[e][a]];
            X[a] = X_[lconn[e][a]];
        }
        frames[e] = shellbt::make_frame(X);
        for (int a = 0; a < 4; ++a)
            for (int d = 0; d < 3; ++d) {
                m[6 * lconn[e][a] + d] += mass_scale_[e] * mass_[e].mass[a];
                m[6 * lconn[e][a] + 3 + d] += mass_scale_[e] * mass_[e].inertia[a];
            }
    }
    std::vector<double> w(m.size());
    for (std::size_t i = 0; i < m.size(); ++i) w[i] = 1.0 / std::sqrt(m[i]);
    const int n = static_cast<int>(w.size());
    ShellStiffnessOp op(consts_, frames, lconn, w);
    // Ritz value theta: an eigenvalue lies within tol theta of it, so omega_max^2 <= theta (1 + tol).
    // 1e-4 (omega_max to 5e-5) takes 7 restarts, 161 operator applications on a 70 x 70 plate (2 s
    // on the loaded machine; a thesis part of ~1,000 elements: under 0.1 s).
    const double tol = 1e-4;
    Spectra::SymEigsSolver<ShellStiffnessOp> eigs(op, 1, std::min(n, 40));
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, 2000, tol);
    if (eigs.info() == Spectra::CompInfo::Successful && eigs.eigenvalues()[0] > 0.0)
        return std::sqrt(eigs.eigenvalues()[0] * (1.0 + tol));
    // Not converged: the element eigenvalue inequality (each element alone with its lumped masses)
    // gives a guaranteed, pessimistic bound.
    double wmax = 0.0;
    const int nd = triangles_ ? 3 : 4;  // distinct nodes (a triangle's repeated node folded in)
    for (int e = 0; e < size(); ++e) {
        std::array<Vec3, 4> X;
        for (int a = 0; a < 4; ++a) X[a] = X_[lconn[e][a]];
        const auto K = shellbt::linear_stiffness(consts_, X);
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * nd, 6 * nd);
        for (int I = 0; I < 4; ++I)
            for (int J = 0; J < 4; ++J)
                A.block<6, 6>(6 * std::min(I, nd - 1), 6 * std::min(J, nd - 1)) += K.block<6, 6>(6 * I, 6 * J);
        Eigen::VectorXd sc(6 * nd);
        for (int a = 0; a < nd; ++a)
            for (int d = 0; d < 6; ++d)
                sc[6 * a + d] = 1.0 / std::sqrt(mass_scale_[e] * (d < 3 ? mass_[e].mass[a] : mass_[e].inertia[a]));
        A = sc.asDiagonal() * A * sc.asDiagonal();
        const Eigen::MatrixXd symmetric = 0.5 * (A + A.transpose());  // a named matrix: core/eigen_instances.hpp
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(symmetric, Eigen::EigenvaluesOnly);
        wmax = std::max(wmax, std::sqrt(eig.eigenvalues().maxCoeff()));
    }
    std::fprintf(stderr, "shell part '%s': stability measurement did not converge; element bound used\n", part.c_str());
    return wmax;
}

double ShellGroup::add_lumped_mass(NodalState& s) const {
    double added = 0.0;
    for (int e = 0; e < size(); ++e) {
        double m = 0.0;
        for (int a = 0; a < 4; ++a) {
            const int node = conn_[e][a];
            s.mass[node] += mass_scale_[e] * mass_[e].mass[a];
            s.inertia[s.rot_index[node]] += mass_scale_[e] * mass_[e].inertia[a];
            m += mass_[e].mass[a];
        }
        added += (mass_scale_[e] - 1.0) * m;
    }
    return added;
}

double ShellGroup::mass() const {
    double m = 0.0;
    for (const auto& me : mass_)
        for (double v : me.mass) m += v;
    return m;
}

void ShellGroup::set_mass_scaling(std::vector<double> factor) {
    if (static_cast<int>(factor.size()) != size()) throw InputError("mass scaling: one factor per element needed");
    mass_scale_ = std::move(factor);
    for (int k = 0; k < size(); ++k) sqrt_mass_scale_[k] = std::sqrt(mass_scale_[order_[k]]);
}

std::vector<double> ShellGroup::surface_stress(int p) const {
    if (p < 0 || p >= shellbt::kPoints) throw InputError(fmt::format("shell surface stress: point {} (0, 1, 2)", p));
    std::vector<double> vm(size());
    for (int e = 0; e < size(); ++e) vm[e] = std::sqrt(vm_sq_[position_[e]][p]);
    return vm;
}

std::vector<double> ShellGroup::element_stress() const {
    std::vector<double> vm(size());
    for (int e = 0; e < size(); ++e) {
        const auto& v = vm_sq_[position_[e]];
        vm[e] = std::sqrt(std::max({v[0], v[1], v[2]}));
    }
    return vm;
}

std::vector<std::pair<std::string, std::vector<double>>> ShellGroup::cell_fields() const {
    return {{"von_mises_bottom", surface_stress(0)}, {"von_mises_mid", surface_stress(1)},
            {"von_mises_top", surface_stress(2)}};
}

GroupForceResult ShellGroup::internal_forces(NodalState& s, bool compute_dt) {
    const int n = size();
    const int nn = static_cast<int>(nodes_.size());
    // Node pass: the step's increments against the last evaluation (positions and rotations), the
    // mid-step positions; then the new state becomes the "last" one.
    par::for_each_index(nn, nn >= par::kParallelMin, [&](int k) {
        const int node = nodes_[k];
        const Vec3& x = s.x[node];
        du_[k] = x - x_prev_[k];
        x_mid_[k] = 0.5 * (x + x_prev_[k]);
        x_prev_[k] = x;
        const Mat3& R = s.rotation[s.rot_index[node]];
        dtheta_[k] = shellbt::rotation_increment(R, R_prev_[k]);
        R_prev_[k] = R;
    });
    const shellbt::Constants& c = consts_;
    auto run_chunk = [&](int chunk) {
        ChunkSums p;
        p.dt = std::numeric_limits<double>::infinity();
        std::array<Vec3, 4> xm, xe, du, dth;
        shellbt::Result r;
        const auto [k0, k1] = colouring_.range(chunk);
        for (int k = k0; k < k1; ++k) {
            const auto& cg = kconn_[k];
            const auto& cl = klocal_[k];
            for (int a = 0; a < 4; ++a) {
                xm[a] = x_mid_[cl[a]];
                du[a] = du_[cl[a]];
                dth[a] = dtheta_[cl[a]];
                xe[a] = s.x[cg[a]];
            }
            const shellbt::Frame fm = shellbt::make_frame(xm);
            const shellbt::Frame fe = shellbt::make_frame(xe);
            if (!(fm.area > 0.0) || !(fe.area > 0.0)) {
                if (p.bad_k < 0) p.bad_k = k;
                continue;
            }
            shellbt::update_state(c, fm, du, dth, state_[k]);
            shellbt::forces(c, fe, state_[k], r);
            if (r.bad) {
                if (p.bad_k < 0) p.bad_k = k;
                continue;
            }
            // Direct scatter: no other thread touches these nodes now (colouring).
            for (int a = 0; a < 4; ++a) {
                s.f[cg[a]] += r.force[a];
                s.moment[s.rot_index[cg[a]]] += r.moment[a];
            }
            p.ie += r.strain_energy;
            p.hg += r.hourglass_energy;
            vm_sq_[k] = r.von_mises_sq;
            p.vm_sq = std::max({p.vm_sq, r.von_mises_sq[0], r.von_mises_sq[1], r.von_mises_sq[2]});
            if (compute_dt)  // Table 2-1 shell row on the current nodes; dt ~ sqrt(rho) under mass scaling.
                p.take_step(factor_ * shellbt::critical_time_step(material_, xe, triangles_) * sqrt_mass_scale_[k], k);
        }
        partial_[chunk] = p;
    };
    colouring_.for_each_chunk(n >= par::kParallelMin, run_chunk);
    return combine_chunks(partial_, order_, compute_dt);
}

}  // namespace fem
