#include "explicit/groups.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "element/critical_time_step.hpp"
#include "explicit/parallel.hpp"

namespace fem {

GroupForceResult combine_chunks(const std::vector<ChunkSums>& chunks, const std::vector<int>& order, bool compute_dt) {
    GroupForceResult out;
    int dt_k = -1, bad_k = -1;
    for (const auto& p : chunks) {  // fixed (chunk) order: the same bits on any number of threads
        out.internal_energy += p.ie;
        out.hourglass_energy += p.hg;
        out.viscous_power += p.visc;
        out.max_von_mises = std::max(out.max_von_mises, std::sqrt(p.vm_sq));  // sqrt is monotone: max commutes
        if (p.bad_k >= 0 && bad_k < 0) bad_k = p.bad_k;
        if (p.dt < out.dt_min) {
            out.dt_min = p.dt;
            dt_k = p.dt_k;
        }
    }
    out.bad_element = bad_k >= 0 ? order[bad_k] : -1;
    out.dt_element = dt_k >= 0 ? order[dt_k] : -1;
    if (!compute_dt) out.dt_min = std::numeric_limits<double>::quiet_NaN();
    return out;
}

// --- Hex8Group ---------------------------------------------------------------------------------------

Hex8Group::Hex8Group(const Mesh& mesh, int block, const ElasticMaterial& material, const Hex8Options& options)
    : material_(material),
      kernel_material_(hex8::Hex8Material::from(material, options.hourglass_qm, options.rayleigh_beta,
                                                options.bulk, options.bulk_viscosity)) {
    const ElementBlock& b = mesh.blocks.at(block);
    if (b.shape != ElementShape::Hex8)
        throw InputError(fmt::format("part '{}' (block {}) is {}, not hex8", b.part, block, to_string(b.shape)));
    if (options.hourglass_qm < 0 || options.rayleigh_beta < 0)
        throw InputError(fmt::format("part '{}': hourglass QM and Rayleigh beta must not be negative", b.part));
    part = b.part;
    this->block = block;
    const int n = b.size();
    conn_.resize(n);
    refs_.reserve(n);
    for (int e = 0; e < n; ++e) {
        std::array<Vec3, 8> X;
        for (int a = 0; a < 8; ++a) {
            conn_[e][a] = b.element(e)[a];
            X[a] = mesh.nodes.at(conn_[e][a]);
        }
        const std::string name = fmt::format("part '{}' block {} hex8 element {}", part, block, e);
        refs_.push_back(hex8::make_reference(X, name.c_str()));
        ref_dt_.push_back(cfl::critical_time_step(ElementShape::Hex8, X, material_));
    }
    // Kernel order (see groups.hpp).
    order_ = par::node_order(conn_);
    kconn_.resize(n);
    for (int k = 0; k < n; ++k) kconn_[k] = conn_[order_[k]];
    static_assert(kChunk % hex8::kLanes == 0, "chunks must hold whole blocks of elements");
    packed_.resize((n + hex8::kLanes - 1) / hex8::kLanes);
    for (int k = 0; k < static_cast<int>(packed_.size()) * hex8::kLanes; ++k)
        hex8::pack_lane(hex8::pack(refs_[order_[std::min(k, n - 1)]], kernel_material_), k % hex8::kLanes,
                        packed_[k / hex8::kLanes]);
    mass_scale_.assign(n, 1.0);
    sqrt_mass_scale_.assign(n, 1.0);
    dt_wave_speed_ = cfl::wave_speed(ElementShape::Hex8, material_);
    von_mises_sq_.assign(n, 0.0);
    colouring_ = par::ChunkColouring::build(kconn_, mesh.node_count(), kChunk);
    partial_.resize(colouring_.chunk_count());
    std::vector<char> used(mesh.node_count(), 0);
    for (const auto& c : conn_)
        for (int a : c) used[a] = 1;
    for (int i = 0; i < mesh.node_count(); ++i)
        if (used[i]) nodes_.push_back(i);
}

double Hex8Group::add_lumped_mass(NodalState& s) const {
    // Row-sum lumping of the one-point element: rho V0 / 8 per node (Eq 2-23 in 3D).
    double added = 0.0;
    for (int e = 0; e < size(); ++e) {
        const double m = material_.density * refs_[e].volume;
        for (int a : conn_[e]) s.mass[a] += mass_scale_[e] * m / 8.0;
        added += (mass_scale_[e] - 1.0) * m;
    }
    return added;
}

double Hex8Group::mass() const {
    double m = 0.0;
    for (const auto& r : refs_) m += material_.density * r.volume;
    return m;
}

std::vector<double> Hex8Group::reference_time_steps() const {
    return ref_dt_;  // Table 2-1 on the undeformed element, unscaled
}

void Hex8Group::set_mass_scaling(std::vector<double> factor) {
    if (static_cast<int>(factor.size()) != size()) throw InputError("mass scaling: one factor per element needed");
    mass_scale_ = std::move(factor);
    for (int k = 0; k < size(); ++k) sqrt_mass_scale_[k] = std::sqrt(mass_scale_[order_[k]]);
}

std::vector<double> Hex8Group::element_stress() const {
    std::vector<double> vm(von_mises_sq_.size());
    for (int k = 0; k < size(); ++k) vm[order_[k]] = std::sqrt(von_mises_sq_[k]);
    return vm;
}

GroupForceResult Hex8Group::internal_forces(NodalState& s, bool compute_dt) {
    const int n = size();
    const double beta = kernel_material_.rayleigh_beta;
    const bool bulk_on = kernel_material_.bulk_viscosity;
    const hex8::Hex8Material& kmat = kernel_material_;
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "nodal vectors are 3 contiguous doubles");
    const double* xs = reinterpret_cast<const double*>(s.x.data());
    const double* Xs = reinterpret_cast<const double*>(s.X.data());
    const double* vs = reinterpret_cast<const double*>(s.v.data());
    Vec3* fs = s.f.data();
    // The viscous part of the forces, also into s.fv when the solver books it (exact energy booking).
    const bool book_viscous = !s.fv.empty() && adds_viscous_forces();
    Vec3* fvs = book_viscous ? s.fv.data() : nullptr;

    // One chunk of kChunk consecutive kernel-order elements, in blocks of kLanes elements, one per
    // lane (the kernel does per lane exactly what it does for one element: the results do not
    // depend on the blocking). Node a's component i of the element in lane l is at [i][a][l].
    const bool prefetch = packed_.size() * sizeof(hex8::Hex8PackedBlock) >= (std::size_t{512} << 10);
    auto run_chunk = [&](int c) {
        ChunkSums p;
        p.dt = std::numeric_limits<double>::infinity();
        constexpr int W = hex8::kLanes;
        hex8::Hex8KernelResultBlock r;
        alignas(hex8::kLanesAlign) hex8::Lanes x[3][8], u[3][8], v[3][8], dt_block;  // see hex8::Lanes
        const hex8::Lanes no_rate{};
        const auto [k0, k1] = colouring_.range(c);  // k0 is a multiple of W (kChunk is)
        const int last_block = static_cast<int>(packed_.size()) - 1;
        for (int kb = k0; kb < k1; kb += W) {
            const int lanes = std::min(W, k1 - kb);
            // The packed reference data is the largest stream (312 bytes per element): fetch the
            // block after next now, so that it is in cache when the kernel needs it (the hardware
            // prefetcher alone left the kernel waiting for memory on 100,000 elements).
            // A group whose packed data fits in the L2 cache (< 512 kB, ~1,600 elements: the fingers
            // of rotating_finger_contact) skips it: the data stays in cache from cycle to cycle.
            if (prefetch) {
                const char* next = reinterpret_cast<const char*>(&packed_[std::min(kb / W + 2, last_block)]);
                for (std::size_t b = 0; b < sizeof(hex8::Hex8PackedBlock); b += 64) __builtin_prefetch(next + b);
            }
            hex8::gather(xs, Xs, vs, &kconn_[kb], lanes, x, u, v);
            hex8::internal_force(packed_[kb / W], kmat, u, v, r, book_viscous);
            // Table 2-1 hexahedron on the current coordinates, with the bulk-viscosity Q term:
            // fem::cfl::critical_time_step's formula with the kernel's cheaper exact V_e / A_emax
            // (equal to fem::cfl::hexahedron_length to round-off, tests/explicit).
            if (compute_dt)
                hex8::critical_time_step(x, bulk_on ? r.volumetric_strain_rate : no_rate, dt_wave_speed_, kmat.bulk,
                                         dt_block);
            for (int l = 0; l < lanes; ++l) {
                const int k = kb + l;
                if (!(r.jacobian[l] > 0.0) || !std::isfinite(r.strain_energy[l])) {
                    if (p.bad_k < 0) p.bad_k = k;
                    continue;  // no force from an inverted element (the run stops)
                }
                // Direct scatter: no other thread touches these nodes now (colouring).
                const auto& cn = kconn_[k];
                for (int a = 0; a < 8; ++a) {
                    Vec3& f = fs[cn[a]];
                    f[0] += r.f[0][a][l];
                    f[1] += r.f[1][a][l];
                    f[2] += r.f[2][a][l];
                }
                if (book_viscous)
                    for (int a = 0; a < 8; ++a) {
                        Vec3& f = fvs[cn[a]];
                        f[0] += r.fv[0][a][l];
                        f[1] += r.fv[1][a][l];
                        f[2] += r.fv[2][a][l];
                    }
                p.ie += r.strain_energy[l];
                p.hg += r.hourglass_energy[l];
                p.visc += r.viscous_power[l];
                von_mises_sq_[k] = r.von_mises_sq[l];
                p.vm_sq = std::max(p.vm_sq, r.von_mises_sq[l]);
                if (compute_dt)  // dt ~ sqrt(rho) under mass scaling; stiffness damping lowers it
                    p.take_step(stiffness_damped_step(dt_block[l] * sqrt_mass_scale_[k], beta), k);
            }
        }
        partial_[c] = p;
    };
    colouring_.for_each_chunk(n >= par::kParallelMin, run_chunk);
    return combine_chunks(partial_, order_, compute_dt);
}

// --- BeamGroup ---------------------------------------------------------------------------------------

BeamGroup::BeamGroup(const Mesh& mesh, int block, const ElasticMaterial& material, const BeamOptions& options)
    : material_(material), options_(options) {
    const ElementBlock& b = mesh.blocks.at(block);
    if (b.shape != ElementShape::Beam2)
        throw InputError(fmt::format("part '{}' (block {}) is {}, not beam2", b.part, block, to_string(b.shape)));
    part = b.part;
    this->block = block;
    options_.section.validate(fmt::format("part '{}'", part).c_str());
    const int n = b.size();
    for (int e = 0; e < n; ++e) {
        std::array<int, 2> c{b.element(e)[0], b.element(e)[1]};
        conn_.push_back(c);
        try {
            refs_.push_back(beam::make_reference(mesh.nodes.at(c[0]), mesh.nodes.at(c[1]), options_.orientation));
        } catch (const InputError& err) {
            throw InputError(fmt::format("part '{}' block {} beam element {}: {}", part, block, e, err.what()));
        }
    }
    packed_.resize((n + hex8::kLanes - 1) / hex8::kLanes);
    for (int k = 0; k < static_cast<int>(packed_.size()) * hex8::kLanes; ++k) {
        const auto& r = refs_[std::min(k, n - 1)];
        beam::pack_lane(beam::pack(r, beam::Stiffness::of(r, options_.section, material_)), k % hex8::kLanes,
                        packed_[k / hex8::kLanes]);
    }
    mass_scale_.assign(n, 1.0);
    sqrt_mass_scale_.assign(n, 1.0);
    stress_.assign(n, 0.0);
    wave_speed_ = bar_wave_speed(material_);
    for (const auto& r : refs_)
        transverse_dt_.push_back(beam::transverse_time_step(
            options_.section, material_, r.length, beam::nodal_rotational_inertia(options_.section, material_, r.length)));
}

std::vector<int> BeamGroup::nodes() const {
    std::vector<int> v;
    for (const auto& c : conn_) v.insert(v.end(), c.begin(), c.end());
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

double BeamGroup::add_lumped_mass(NodalState& s) const {
    double added = 0.0;
    for (int e = 0; e < size(); ++e) {
        const double L = refs_[e].length;
        const double m = material_.density * options_.section.area * L;
        const double J = beam::nodal_rotational_inertia(options_.section, material_, L);
        for (int a : conn_[e]) {
            s.mass[a] += mass_scale_[e] * m / 2.0;
            s.inertia[s.rot_index[a]] += mass_scale_[e] * J;
        }
        added += (mass_scale_[e] - 1.0) * m;
    }
    return added;
}

double BeamGroup::mass() const {
    double m = 0.0;
    for (const auto& r : refs_) m += material_.density * options_.section.area * r.length;
    return m;
}

double BeamGroup::rotational_inertia_scaling(int e) const {
    const double L = refs_.at(e).length;
    return beam::nodal_rotational_inertia(options_.section, material_, L) /
           beam::physical_rotational_inertia(options_.section, material_, L);
}

std::string BeamGroup::time_step_rule(int e) const {
    const double axial = cfl::time_step(refs_.at(e).length, wave_speed_);
    return transverse_dt_[e] < axial ? "bending: transverse bound 2/omega" : "axial: Table 2-1 L/c";
}

std::vector<double> BeamGroup::reference_time_steps() const {
    std::vector<double> dt;
    for (const auto& r : refs_)
        dt.push_back(beam::critical_time_step(options_.section, material_, Vec3::Zero(), r.length * r.frame0.col(0)));
    return dt;
}

void BeamGroup::set_mass_scaling(std::vector<double> factor) {
    if (static_cast<int>(factor.size()) != size()) throw InputError("mass scaling: one factor per element needed");
    mass_scale_ = std::move(factor);
    for (int e = 0; e < size(); ++e) sqrt_mass_scale_[e] = std::sqrt(mass_scale_[e]);
}

GroupForceResult BeamGroup::internal_forces(NodalState& s, bool compute_dt) {
    // Few elements (the wire of Table 2-8 has 100): one thread, in blocks of kLanes elements (one per
    // lane, the one-element operations: the same bits), then the forces added element by element.
    GroupForceResult out;
    constexpr int W = hex8::kLanes;
    const int n = size();
    beam::KernelResultBlock r;
    alignas(hex8::kLanesAlign) hex8::Lanes x1[3], x2[3], R1[3][3], R2[3][3];  // see hex8::Lanes
    for (int eb = 0; eb < n; eb += W) {
        const int lanes = std::min(W, n - eb);
        for (int l = 0; l < W; ++l) {
            const auto& c = conn_[eb + std::min(l, lanes - 1)];  // spare lanes repeat the last element
            const Vec3 &xa = s.x[c[0]], &xb = s.x[c[1]];
            const Mat3 &Ra = s.rotation[s.rot_index[c[0]]], &Rb = s.rotation[s.rot_index[c[1]]];
            for (int i = 0; i < 3; ++i) {
                x1[i][l] = xa[i];
                x2[i][l] = xb[i];
                for (int j = 0; j < 3; ++j) {
                    R1[i][j][l] = Ra(i, j);
                    R2[i][j][l] = Rb(i, j);
                }
            }
        }
        beam::internal_force(packed_[eb / W], x1, x2, R1, R2, r);
        for (int l = 0; l < lanes; ++l) {
            const int e = eb + l;
            const double length = r.length[l];
            if (!(length > 0.0) || !std::isfinite(length) || !std::isfinite(r.strain_energy[l])) {
                if (out.bad_element < 0) out.bad_element = e;
                continue;
            }
            const int a = conn_[e][0], b = conn_[e][1];
            const Vec3 f(r.force[0][l], r.force[1][l], r.force[2][l]);
            s.f[a] += f;
            s.f[b] -= f;
            s.moment[s.rot_index[a]] += Vec3(r.moment[0][0][l], r.moment[0][1][l], r.moment[0][2][l]);
            s.moment[s.rot_index[b]] += Vec3(r.moment[1][0][l], r.moment[1][1][l], r.moment[1][2][l]);
            out.internal_energy += r.strain_energy[l];
            stress_[e] = r.max_stress[l];
            out.max_von_mises = std::max(out.max_von_mises, r.max_stress[l]);
            if (compute_dt) {
                // Table 2-1 beam row, L/c on the current length (fem::cfl::time_step), or the cached
                // transverse bound of a stubby element (see beam_corotational.hpp).
                const double dt = std::min(cfl::time_step(length, wave_speed_), transverse_dt_[e]) * sqrt_mass_scale_[e];
                if (dt < out.dt_min) {
                    out.dt_min = dt;
                    out.dt_element = e;
                }
            }
        }
    }
    if (!compute_dt) out.dt_min = std::numeric_limits<double>::quiet_NaN();
    return out;
}

// --- PointMassGroup ----------------------------------------------------------------------------------

PointMassGroup::PointMassGroup(std::string part_name, std::vector<int> nodes, std::vector<double> masses,
                               std::vector<double> rotational_inertia)
    : nodes_(std::move(nodes)), masses_(std::move(masses)), inertia_(std::move(rotational_inertia)) {
    part = std::move(part_name);
    if (masses_.size() == 1 && nodes_.size() > 1) masses_.assign(nodes_.size(), masses_[0]);
    if (inertia_.size() == 1 && nodes_.size() > 1) inertia_.assign(nodes_.size(), inertia_[0]);
    if (masses_.size() != nodes_.size())
        throw InputError(fmt::format("point masses of part '{}': {} nodes but {} masses", part, nodes_.size(),
                                     masses_.size()));
    if (!inertia_.empty() && inertia_.size() != nodes_.size())
        throw InputError(fmt::format("point masses of part '{}': {} nodes but {} rotational inertias", part,
                                     nodes_.size(), inertia_.size()));
    for (std::size_t i = 0; i < masses_.size(); ++i)
        if (!(masses_[i] > 0.0) || (!inertia_.empty() && inertia_[i] < 0.0))
            throw InputError(fmt::format("point mass {} of part '{}' on node {}: mass {:.4g} must be positive and "
                                         "inertia not negative",
                                         i, part, nodes_[i], masses_[i]));
    for (double j : inertia_) has_rotation_ = has_rotation_ || j > 0.0;
}

double PointMassGroup::add_lumped_mass(NodalState& s) const {
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        s.mass.at(nodes_[i]) += masses_[i];
        if (!inertia_.empty() && inertia_[i] > 0.0) s.inertia[s.rot_index[nodes_[i]]] += inertia_[i];
    }
    return 0.0;
}

double PointMassGroup::mass() const {
    double m = 0.0;
    for (double v : masses_) m += v;
    return m;
}

std::vector<double> PointMassGroup::reference_time_steps() const {
    return std::vector<double>(nodes_.size(), std::numeric_limits<double>::infinity());
}

}  // namespace fem
