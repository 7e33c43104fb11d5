#include "explicit/tet_groups.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "explicit/solver.hpp"

namespace fem {

namespace {
constexpr ElementShape shape_of(int n) { return n == 4 ? ElementShape::Tet4 : ElementShape::Tet10; }
// Below this many elements the loop runs on one thread (fork/join costs more than the work).
constexpr int kTetParallelMin = 1024;

}  // namespace

template <int N, int Q>
TetGroup<N, Q>::TetGroup(const Mesh& mesh, int block, const ElasticMaterial& material, const TetGroupOptions& options)
    : material_(material),
      kmat_(hex8::Hex8Material::from(material, 0.0, options.rayleigh_beta, options.bulk, options.bulk_viscosity)),
      beta_(options.rayleigh_beta) {
    constexpr ElementShape shape = shape_of(N);
    const ElementBlock& b = mesh.blocks.at(block);
    if (b.shape != shape)
        throw InputError(fmt::format("part '{}' (block {}) is {}, not {}", b.part, block, to_string(b.shape),
                                     to_string(shape)));
    if (options.rayleigh_beta < 0)
        throw InputError(fmt::format("part '{}': Rayleigh beta must not be negative", b.part));
    part = b.part;
    this->block = block;
    const int n = b.size();
    conn_.resize(n);
    refs_.reserve(n);
    mass_.resize(n);
    element_ratio_.resize(n);
    element_omega_.resize(n);
    table_dt_.resize(n);
    std::array<Vec3, N> X;
    for (int e = 0; e < n; ++e) {
        for (int a = 0; a < N; ++a) {
            conn_[e][a] = b.element(e)[a];
            X[a] = mesh.nodes.at(conn_[e][a]);
        }
        const std::string name = fmt::format("part '{}' block {} {} element {}", part, block, to_string(shape), e);
        if constexpr (N == 4) {
            refs_.push_back(tet::make_tet4_reference(X, name.c_str()));
            mass_[e] = tet::tet4_lumped_mass(X, material_.density);
        } else {
            refs_.push_back(tet::make_tet10_reference(X, name.c_str()));
            mass_[e] = tet::tet10_lumped_mass(X, material_.density);
        }
        // The element's own stability limit 2 / omega_e against the Table 2-1 rule (tet_groups.hpp).
        const double omega = tet::element_omega_max(tet::linear_stiffness(refs_[e], kmat_), mass_[e]);
        const double dt_table = cfl::critical_time_step(shape, X, material_);
        table_dt_[e] = dt_table;
        element_omega_[e] = omega;
        element_ratio_[e] = (2.0 / omega) / dt_table;
    }
    mass_scale_.assign(n, 1.0);
    von_mises_.assign(n, 0.0);
    cauchy_.assign(n, Mat3::Zero());
    ie_.assign(n, 0.0);
    visc_.assign(n, 0.0);
    dt_.assign(n, std::numeric_limits<double>::infinity());
    bad_.assign(n, 0);
    fe_.resize(static_cast<std::size_t>(n) * N);
    scatter_ = par::NodeScatter::build(conn_, mesh.node_count());
}

template <int N, int Q>
bool TetGroup<N, Q>::set_stability_factor(double r) {
    if (!(r > 0.0 && r <= 1.0)) throw InputError(fmt::format("part '{}': stability factor {} not in (0, 1]", part, r));
    factor_ = r;
    return true;
}

template <int N, int Q>
double TetGroup<N, Q>::element_omega_bound() const {
    double w = 0.0;  // omega_e ~ 1 / sqrt(density): selective mass scaling lowers it
    for (int e = 0; e < size(); ++e) w = std::max(w, element_omega_[e] / std::sqrt(mass_scale_[e]));
    return w;
}

template <int N, int Q>
double TetGroup<N, Q>::add_lumped_mass(NodalState& s) const {
    double added = 0.0;
    for (int e = 0; e < size(); ++e) {
        double m = 0.0;
        for (int a = 0; a < N; ++a) {
            s.mass[conn_[e][a]] += mass_scale_[e] * mass_[e][a];
            m += mass_[e][a];
        }
        added += (mass_scale_[e] - 1.0) * m;
    }
    return added;
}

template <int N, int Q>
double TetGroup<N, Q>::mass() const {
    double m = 0.0;
    for (const auto& me : mass_)
        for (double x : me) m += x;
    return m;
}

template <int N, int Q>
std::vector<double> TetGroup<N, Q>::reference_time_steps() const {
    std::vector<double> dt(table_dt_.size());
    for (std::size_t e = 0; e < dt.size(); ++e) dt[e] = table_dt_[e];  // unscaled
    return dt;
}

template <int N, int Q>
void TetGroup<N, Q>::set_mass_scaling(std::vector<double> factor) {
    if (static_cast<int>(factor.size()) != size()) throw InputError("mass scaling: one factor per element needed");
    mass_scale_ = std::move(factor);
}

template <int N, int Q>
GroupForceResult TetGroup<N, Q>::internal_forces(NodalState& s, bool compute_dt) {
    constexpr ElementShape shape = shape_of(N);
    const int n = size();
    // The viscous parts go to their own slots when the solver books them (NodalState::fv).
    const bool book_viscous = !s.fv.empty() && adds_viscous_forces();
    if (book_viscous && fve_.size() != fe_.size()) fve_.assign(fe_.size(), Vec3::Zero());
#pragma omp parallel for schedule(dynamic, 256) if (n >= kTetParallelMin)
    for (int e = 0; e < n; ++e) {
        std::array<Vec3, N> x, v;
        for (int a = 0; a < N; ++a) {
            x[a] = s.x[conn_[e][a]];
            v[a] = s.v[conn_[e][a]];
        }
        tet::Result<N> r;
        tet::internal_force(refs_[e], kmat_, std::span<const Vec3>(x), std::span<const Vec3>(v), r);
        Vec3* fe = &fe_[static_cast<std::size_t>(e) * N];
        bad_[e] = !(r.min_jacobian > 0.0) || !std::isfinite(r.strain_energy);
        if (bad_[e]) {
            for (int a = 0; a < N; ++a) fe[a].setZero();
            if (book_viscous)
                for (int a = 0; a < N; ++a) fve_[static_cast<std::size_t>(e) * N + a].setZero();
            ie_[e] = visc_[e] = 0.0;
            continue;
        }
        for (int a = 0; a < N; ++a) fe[a] = r.force[a];
        if (book_viscous)
            for (int a = 0; a < N; ++a) fve_[static_cast<std::size_t>(e) * N + a] = r.viscous_force[a];
        ie_[e] = r.strain_energy;
        visc_[e] = r.viscous_power;
        von_mises_[e] = r.von_mises;
        cauchy_[e] = r.cauchy;
        if (compute_dt) {
            // Table 2-1 on the current nodes (with the Q term) times the measured stability factor.
            double dt = factor_ *
                        cfl::critical_time_step(shape, x, material_, kmat_.bulk_viscosity ? r.volumetric_strain_rate : 0.0,
                                                kmat_.bulk) *
                        std::sqrt(mass_scale_[e]);
            if (beta_ > 0.0) {
                const double xi = beta_ / dt;  // beta omega / 2 with omega = 2 / dt
                dt *= std::sqrt(1.0 + xi * xi) - xi;
            }
            dt_[e] = dt;
        }
    }
    scatter_.add_to(fe_, s.f, n >= kTetParallelMin);
    if (book_viscous) scatter_.add_to(fve_, s.fv, n >= kTetParallelMin);
    GroupForceResult out;
    for (int e = 0; e < n; ++e) {  // fixed order: the same bits on any number of threads
        if (bad_[e]) {
            if (out.bad_element < 0) out.bad_element = e;
            continue;
        }
        out.internal_energy += ie_[e];
        out.viscous_power += visc_[e];
        out.max_von_mises = std::max(out.max_von_mises, von_mises_[e]);
        if (compute_dt && dt_[e] < out.dt_min) {
            out.dt_min = dt_[e];
            out.dt_element = e;
        }
    }
    if (!compute_dt) out.dt_min = std::numeric_limits<double>::quiet_NaN();
    return out;
}

template class TetGroup<4, 1>;
template class TetGroup<10, 4>;

void add_tets(ExplicitModel& model, std::string_view part, const ElasticMaterial& material, const TetGroupOptions& options) {
    const Mesh& mesh = model.mesh();
    const std::vector<int> blocks = mesh.blocks_of_part(part);  // InputError when none
    for (int b : blocks) {
        const ElementShape shape = mesh.blocks[b].shape;
        if (shape != ElementShape::Tet4 && shape != ElementShape::Tet10)
            throw InputError(fmt::format("add_tets: part '{}' has a {} block ({}); only tet4 and tet10 blocks are "
                                         "tetrahedral parts",
                                         part, to_string(shape), b));
    }
    for (int b : blocks) {
        if (mesh.blocks[b].shape == ElementShape::Tet4)
            model.add_group(std::make_unique<Tet4Group>(mesh, b, material, options));
        else
            model.add_group(std::make_unique<Tet10Group>(mesh, b, material, options));
    }
}

}  // namespace fem
