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
    // Kernel order and the packed blocks (see tet_groups.hpp).
    order_ = par::node_order(conn_);
    kconn_.resize(n);
    for (int k = 0; k < n; ++k) kconn_[k] = conn_[order_[k]];
    static_assert(kChunk % hex8::kLanes == 0, "chunks must hold whole blocks of elements");
    {
        const int blocks = (n + hex8::kLanes - 1) / hex8::kLanes;
        std::vector<char> straight(n, 0);  // kernel order
        if constexpr (N == 10)
            for (int k = 0; k < n; ++k) {
                std::array<Vec3, N> Xk;
                for (int a = 0; a < N; ++a) Xk[a] = mesh.nodes.at(kconn_[k][a]);
                straight[k] = tet::straight_sided(Xk);
            }
        slot_.resize(blocks);
        for (int kb = 0; kb < blocks; ++kb) {
            bool all = true;
            for (int l = 0; l < hex8::kLanes; ++l) all = all && straight[std::min(kb * hex8::kLanes + l, n - 1)];
            if (all) {
                slot_[kb] = -1 - static_cast<int>(straight_.size());
                straight_.emplace_back();
            } else {
                slot_[kb] = static_cast<int>(packed_.size());
                packed_.emplace_back();
            }
        }
        for (int k = 0; k < blocks * hex8::kLanes; ++k) {
            const auto& ref = refs_[order_[std::min(k, n - 1)]];
            const int s = slot_[k / hex8::kLanes];
            if constexpr (N == 10) {
                if (s < 0) {
                    tet::pack_lane(tet::pack_straight(ref), k % hex8::kLanes, straight_[-1 - s]);
                    continue;
                }
            }
            tet::pack_lane(tet::pack(ref), k % hex8::kLanes, packed_[s]);
        }
    }
    step_scale_.resize(n);
    for (int k = 0; k < n; ++k) step_scale_[k] = element_ratio_[order_[k]];
    von_mises_sq_.assign(n, 0.0);
    dt_wave_speed_ = cfl::wave_speed(shape, material_);
    colouring_ = par::ChunkColouring::build(kconn_, mesh.node_count(), kChunk);
    partial_.resize(colouring_.chunk_count());
    std::vector<char> used(mesh.node_count(), 0);
    for (const auto& c : conn_)
        for (int a : c) used[a] = 1;
    for (int i = 0; i < mesh.node_count(); ++i)
        if (used[i]) nodes_.push_back(i);
}

template <int N, int Q>
bool TetGroup<N, Q>::set_stability_factor(double r) {
    // Any positive factor: the reference steps are element bounds, which the assembled limit exceeds
    // (r >= 1 when these elements control; tet_groups.hpp).
    if (!(r > 0.0 && std::isfinite(r))) throw InputError(fmt::format("part '{}': stability factor {} not positive", part, r));
    factor_ = r;
    return true;
}

template <int N, int Q>
std::string TetGroup<N, Q>::time_step_rule(int e) const {
    return fmt::format("element limit 2/omega_e = {:.3f} x Table 2-1 altitude, on the current {}", element_ratio_.at(e),
                       N == 10 ? "deformation at the integration points" : "altitude");
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
    for (std::size_t e = 0; e < dt.size(); ++e) dt[e] = element_ratio_[e] * table_dt_[e];  // 2 / omega_e, unscaled
    return dt;
}

template <int N, int Q>
void TetGroup<N, Q>::set_mass_scaling(std::vector<double> factor) {
    if (static_cast<int>(factor.size()) != size()) throw InputError("mass scaling: one factor per element needed");
    mass_scale_ = std::move(factor);
    for (int k = 0; k < size(); ++k) step_scale_[k] = element_ratio_[order_[k]] * std::sqrt(mass_scale_[order_[k]]);
}

template <int N, int Q>
std::vector<double> TetGroup<N, Q>::element_stress() const {
    std::vector<double> vm(von_mises_sq_.size());
    for (int k = 0; k < size(); ++k) vm[order_[k]] = std::sqrt(von_mises_sq_[k]);
    return vm;
}

template <int N, int Q>
GroupForceResult TetGroup<N, Q>::internal_forces(NodalState& s, bool compute_dt) {
    const int n = size();
    constexpr int W = hex8::kLanes;
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "nodal vectors are 3 contiguous doubles");
    const double* xs = reinterpret_cast<const double*>(s.x.data());
    const double* Xs = reinterpret_cast<const double*>(s.X.data());
    const double* vs = reinterpret_cast<const double*>(s.v.data());
    Vec3* fs = s.f.data();
    // The viscous part of the forces, also into s.fv when the solver books it (exact energy booking).
    const bool book_viscous = !s.fv.empty() && adds_viscous_forces();
    Vec3* fvs = book_viscous ? s.fv.data() : nullptr;
    const bool bulk_on = kmat_.bulk_viscosity;

    // One chunk of kChunk consecutive kernel-order elements, in blocks of W elements, one per lane.
    auto run_chunk = [&](int c) {
        ChunkSums p;
        p.dt = std::numeric_limits<double>::infinity();
        tet::TetKernelResultBlock<N> r;
        alignas(hex8::kLanesAlign) hex8::Lanes x[3][4], u[3][N], v[3][N], dt_block;  // see hex8::Lanes
        const hex8::Lanes no_rate{};
        const auto [k0, k1] = colouring_.range(c);  // k0 is a multiple of W (kChunk is)
        const int last_block = static_cast<int>(slot_.size()) - 1;
        for (int kb = k0; kb < k1; kb += W) {
            const int lanes = std::min(W, k1 - kb);
            {  // the block after next into the cache (the packed data is the largest stream)
                const int s = slot_[std::min(kb / W + 2, last_block)];
                const char* next = s >= 0 ? reinterpret_cast<const char*>(&packed_[s])
                                          : reinterpret_cast<const char*>(&straight_[-1 - s]);
                const std::size_t size = s >= 0 ? sizeof(tet::TetPackedBlock<Q>) : sizeof(tet::TetPackedBlock<1>);
                for (std::size_t b = 0; b < size; b += 64) __builtin_prefetch(next + b);
            }
            tet::gather<N>(xs, Xs, vs, &kconn_[kb], lanes, x, u, v);  // spare lanes repeat the last element
            const int s = slot_[kb / W];
            if constexpr (N == 10) {
                if (s < 0) tet::internal_force(straight_[-1 - s], kmat_, u, v, r, book_viscous);
                else tet::internal_force(packed_[s], kmat_, u, v, r, book_viscous);
            } else {
                tet::internal_force(packed_[s], kmat_, u, v, r, book_viscous);
            }
            // Table 2-1 tetrahedron on the current deformation, with the bulk-viscosity Q term: the
            // tet4 on its corners' altitude, the tet10 on the corner tetrahedron mapped by the
            // Jacobian at each of its 4 points (tet::critical_time_step_tet10: its corners alone can
            // flatten while the element is barely strained).
            if (compute_dt) {
                if constexpr (N == 10)
                    tet::critical_time_step_tet10(x, u, bulk_on ? r.volumetric_strain_rate : no_rate, dt_wave_speed_, kmat_.bulk,
                                                  dt_block);
                else
                    tet::critical_time_step(x, bulk_on ? r.volumetric_strain_rate : no_rate, dt_wave_speed_, kmat_.bulk,
                                            dt_block);
            }
            for (int l = 0; l < lanes; ++l) {
                const int k = kb + l;
                if (!(r.min_jacobian[l] > 0.0) || !std::isfinite(r.strain_energy[l])) {
                    if (p.bad_k < 0) p.bad_k = k;
                    continue;  // no force from an inverted element (the run stops)
                }
                // Direct scatter: no other thread touches these nodes now (colouring). The viscous
                // part in the same pass over the nodes (each array gets its sums in the same order).
                const auto& cn = kconn_[k];
                if (book_viscous) {
                    for (int a = 0; a < N; ++a) {
                        Vec3& f = fs[cn[a]];
                        Vec3& fv = fvs[cn[a]];
                        f[0] += r.f[0][a][l];
                        f[1] += r.f[1][a][l];
                        f[2] += r.f[2][a][l];
                        fv[0] += r.fv[0][a][l];
                        fv[1] += r.fv[1][a][l];
                        fv[2] += r.fv[2][a][l];
                    }
                } else {
                    for (int a = 0; a < N; ++a) {
                        Vec3& f = fs[cn[a]];
                        f[0] += r.f[0][a][l];
                        f[1] += r.f[1][a][l];
                        f[2] += r.f[2][a][l];
                    }
                }
                p.ie += r.strain_energy[l];
                p.visc += r.viscous_power[l];
                von_mises_sq_[k] = r.von_mises_sq[l];
                p.vm_sq = std::max(p.vm_sq, r.von_mises_sq[l]);
                // The element's own limit carried by its Table 2-1 step, mass scaling, the measured
                // factor (tet_groups.hpp), then the stiffness-damping reduction.
                if (compute_dt) p.take_step(stiffness_damped_step(factor_ * dt_block[l] * step_scale_[k], beta_), k);
            }
        }
        partial_[c] = p;
    };
    colouring_.for_each_chunk(n >= kTetParallelMin, run_chunk);
    return combine_chunks(partial_, order_, compute_dt);
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
