#include "explicit/solver.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <Spectra/SymEigsSolver.h>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "element/critical_time_step.hpp"
#include "element/hex8_explicit.hpp"
#include "explicit/node_update.hpp"
#include "explicit/parallel.hpp"
#include "io/atomic_file.hpp"
#include "io/hdf5.hpp"

namespace fem {

// ===================================================================================================
// ExplicitModel
// ===================================================================================================

ExplicitModel::ExplicitModel(Mesh mesh) : mesh_(std::move(mesh)) {
    validate(mesh_);
    fixed_.assign(mesh_.node_count(), 0u);
}

void ExplicitModel::check_nodes(const std::vector<int>& nodes, const char* what) const {
    if (nodes.empty()) throw InputError(fmt::format("{}: empty node list", what));
    for (int n : nodes)
        if (n < 0 || n >= mesh_.node_count())
            throw InputError(fmt::format("{}: node {} out of range (the mesh has {} nodes)", what, n,
                                         mesh_.node_count()));
}

void ExplicitModel::add_hex8(std::string_view part, const ElasticMaterial& material, const Hex8Options& options) {
    for (int b : mesh_.blocks_of_part(part)) groups_.push_back(std::make_unique<Hex8Group>(mesh_, b, material, options));
}

void ExplicitModel::add_beams(std::string_view part, const ElasticMaterial& material, const BeamOptions& options) {
    for (int b : mesh_.blocks_of_part(part)) groups_.push_back(std::make_unique<BeamGroup>(mesh_, b, material, options));
}

void ExplicitModel::add_shells(std::string_view part, const ElasticMaterial& material, const ShellOptions& options) {
    for (int b : mesh_.blocks_of_part(part))
        groups_.push_back(std::make_unique<ShellGroup>(mesh_, b, material, options));
}

void ExplicitModel::add_point_mass(const std::string& part, int node, double mass, double rotational_inertia) {
    check_nodes({node}, fmt::format("point mass of part '{}'", part).c_str());
    if (finalized_) throw InputError("add_point_mass after the solver was created");
    auto& d = point_data_[part];
    d.first.push_back(node);
    d.second.first.push_back(mass);
    d.second.second.push_back(rotational_inertia);
}

void ExplicitModel::add_point_masses(std::string_view part, double mass_each, double rot_each) {
    for (int b : mesh_.blocks_of_part(part)) {
        const auto& blk = mesh_.blocks[b];
        if (blk.shape != ElementShape::Point1)
            throw InputError(fmt::format("add_point_masses: part '{}' block {} is {}, not point1", part, b,
                                         to_string(blk.shape)));
        for (int e = 0; e < blk.size(); ++e) add_point_mass(std::string(part), blk.element(e)[0], mass_each, rot_each);
    }
}

void ExplicitModel::add_group(std::unique_ptr<ElementGroup> group) { groups_.push_back(std::move(group)); }

void ExplicitModel::finalize() {
    if (finalized_) return;
    finalized_ = true;
    for (auto& [part, d] : point_data_) {
        bool rot = false;
        for (double j : d.second.second) rot = rot || j > 0;
        groups_.push_back(std::make_unique<PointMassGroup>(part, d.first, d.second.first,
                                                           rot ? d.second.second : std::vector<double>{}));
    }
    if (groups_.empty()) throw InputError("explicit model has no parts: add hex8, tetrahedra, shells, beams or point masses");
    for (const auto& m : motions_)
        if (!m.part.empty())
            for (const auto& g : groups_)
                if (g->part == m.part)
                    throw InputError(fmt::format("part '{}' is rigid (add_rigid_part) and also has {} elements", m.part,
                                                 g->kind()));
}

void ExplicitModel::fix(const std::vector<int>& nodes, Dofs dofs) {
    check_nodes(nodes, "fix");
    for (int n : nodes) fixed_[n] |= dofs.mask;
}

void ExplicitModel::prescribe_velocity(const std::vector<int>& nodes, int dof, double value, Curve curve) {
    check_nodes(nodes, "prescribe_velocity");
    if (dof < 0 || dof > 2) throw InputError(fmt::format("prescribe_velocity: dof {} (only 0, 1, 2: x, y, z)", dof));
    prescribed_.push_back({nodes, dof, value, std::move(curve), false});
}

void ExplicitModel::prescribe_displacement(const std::vector<int>& nodes, int dof, double value, Curve curve) {
    check_nodes(nodes, "prescribe_displacement");
    if (dof < 0 || dof > 2)
        throw InputError(fmt::format("prescribe_displacement: dof {} (only 0, 1, 2: x, y, z)", dof));
    prescribed_.push_back({nodes, dof, value, std::move(curve), true});
}

void ExplicitModel::prescribe_motion(const std::vector<int>& nodes, RigidMotion motion) {
    check_nodes(nodes, "prescribe_motion");
    motions_.push_back({nodes, std::move(motion), {}, {}});
}

void ExplicitModel::prescribe_motion(const std::vector<int>& nodes,
                                     std::function<Vec3(const Vec3& X, double t)> position) {
    check_nodes(nodes, "prescribe_motion");
    if (!position) throw InputError("prescribe_motion: empty position function");
    motions_.push_back({nodes, {}, std::move(position), {}});
}

void ExplicitModel::add_rigid_part(std::string_view part, RigidMotion motion) {
    for (const auto& m : motions_)
        if (m.part == part) throw InputError(fmt::format("add_rigid_part: part '{}' is already rigid", part));
    motions_.push_back({mesh_.nodes_of_part(part), std::move(motion), {}, std::string(part)});  // throws for an unknown part
}

ForceProvider& ExplicitModel::add_force_provider(std::unique_ptr<ForceProvider> provider) {
    if (!provider) throw InputError("add_force_provider: null provider");
    providers_.push_back(std::move(provider));
    return *providers_.back();
}

void ExplicitModel::add_nodal_force(const std::vector<int>& nodes, const Vec3& force, Curve curve) {
    check_nodes(nodes, "add_nodal_force");
    loads_.push_back({nodes, force, std::move(curve), false});
}

void ExplicitModel::add_nodal_moment(const std::vector<int>& nodes, const Vec3& moment, Curve curve) {
    check_nodes(nodes, "add_nodal_moment");
    loads_.push_back({nodes, moment, std::move(curve), true});
}

void ExplicitModel::set_gravity(const Vec3& g, double t_on) { set_gravity(g, Curve::step(t_on)); }

void ExplicitModel::set_gravity(const Vec3& g, Curve curve) {
    if (!g.allFinite()) throw InputError("set_gravity: the acceleration is not finite");
    gravity_ = g;
    gravity_curve_ = std::move(curve);
}

namespace {
// The global axis (0, 1, 2) of an axis-aligned normal; InputError otherwise.
int symmetry_axis(const Vec3& normal) {
    const double len = normal.norm();
    if (!(len > 0.0) || !normal.allFinite())
        throw InputError("symmetry plane: the normal has zero length or is not finite");
    int axis = 0;
    normal.cwiseAbs().maxCoeff(&axis);
    if (std::abs(normal[axis]) < len * (1.0 - 1e-12))
        throw InputError(fmt::format("symmetry plane: normal ({}, {}, {}) is not along a global axis; only planes "
                                     "normal to x, y or z can be expressed (fixed global DOFs)",
                                     normal.x(), normal.y(), normal.z()));
    return axis;
}
}  // namespace

void ExplicitModel::add_symmetry_plane(const Vec3& normal, const std::vector<int>& nodes) {
    const int a = symmetry_axis(normal);
    check_nodes(nodes, "symmetry plane");
    // The normal translation, and the rotations about the two in-plane axes.
    const unsigned mask = (1u << a) | (1u << (3 + (a + 1) % 3)) | (1u << (3 + (a + 2) % 3));
    for (int n : nodes) fixed_[n] |= mask;
}

std::vector<int> ExplicitModel::add_symmetry_plane(const Vec3& normal, const Vec3& point, double tolerance) {
    const int a = symmetry_axis(normal);
    if (tolerance <= 0.0) {
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const Vec3& X : mesh_.nodes) lo = lo.cwiseMin(X), hi = hi.cwiseMax(X);
        tolerance = 1e-9 * (hi - lo).norm();
    }
    const std::vector<int> nodes =
        mesh_.select_nodes([&](const Vec3& X) { return std::abs(X[a] - point[a]) <= tolerance; });
    if (nodes.empty())
        throw InputError(fmt::format("symmetry plane {} = {}: no node within {:.3g} of it", "xyz"[a], point[a],
                                     tolerance));
    add_symmetry_plane(normal, nodes);
    return nodes;
}

void ExplicitModel::set_mass_damping(std::string_view part, double alpha) {
    if (!(alpha >= 0.0)) throw InputError(fmt::format("mass damping of part '{}': alpha = {} must be >= 0", part, alpha));
    damping_[std::string(part)] = alpha;
}

void ExplicitModel::set_mass_damping(double alpha) {
    if (!(alpha >= 0.0)) throw InputError(fmt::format("mass damping: alpha = {} must be >= 0", alpha));
    global_alpha_ = alpha;
}

void ExplicitModel::set_initial_velocity(const std::vector<int>& nodes, const Vec3& v) {
    check_nodes(nodes, "set_initial_velocity");
    if (v0_.empty()) v0_.assign(mesh_.node_count(), Vec3::Zero());
    for (int n : nodes) v0_[n] = v;
}

void ExplicitModel::set_initial_velocity(const std::function<Vec3(const Vec3&)>& f) {
    v0_.resize(mesh_.node_count());
    for (int n = 0; n < mesh_.node_count(); ++n) v0_[n] = f(mesh_.nodes[n]);
}

void ExplicitModel::set_initial_angular_velocity(const std::vector<int>& nodes, const Vec3& w) {
    check_nodes(nodes, "set_initial_angular_velocity");
    for (int n : nodes) w0_[n] = w;
}

// ===================================================================================================
// RunSummary
// ===================================================================================================

namespace {
// A hexahedron's two lengths at its coordinates x: the bulk viscosity's, cbrt(V), and its Table 2-1
// step's, V / A_max (README "Flat hexahedra and bulk viscosity").
struct HexLengths {
    double viscous = 0.0, step = 0.0;
    double ratio() const { return step > 0.0 ? viscous / step : 1.0; }
};
HexLengths hex_lengths(const std::array<Vec3, 8>& x) {
    return {std::cbrt(hex8::exact_volume(x)), cfl::hexahedron_length(x)};  // the volume the Table 2-1 length divides
}
/// A flat hexahedron's damped step limit within this factor of the run's step bound is warned of: the
/// model (cfl::flat_hexahedron_step_factor) put two of the 63 measured cases on the wrong side of its
/// boundary, 0.02 % and 0.32 % from it.
constexpr double kFlatHexWarnMargin = 1.03;
}  // namespace

std::string RunSummary::text() const {
    std::string s;
    s += fmt::format("==== explicit run '{}' summary ====\n", name);
    s += fmt::format("  nodes {} ({} with rotations), elements {}, threads {}\n", nodes, rotational_nodes, elements,
                     threads);
    s += fmt::format("  mass {:.6g} kg, added by mass scaling {:.4g} kg ({:.3g} %)\n", mass, added_mass,
                     100.0 * added_mass_fraction);
    if (!rigid_parts.empty()) s += fmt::format("  rigid parts: {}\n", fmt::join(rigid_parts, ", "));
    s += fmt::format("  controlling element: part '{}' block {} {} element {}, critical dt {:.4g} s ({})\n",
                     controlling_part, controlling_block, controlling_kind, controlling_element, controlling_dt,
                     controlling_rule);
    if (stability_factor != 1.0)
        s += fmt::format("  measured stability limit of the solid elements: 2/omega_max = {:.4f} x their smallest reference step "
                         "(steps scaled)\n",
                         stability_factor);
    if (!flat_hex.empty()) {
        s += fmt::format("  flat hexahedron with bulk viscosity nearest its damped step limit: {}, cbrt(V) = {:.3g} x V / A_max, "
                         "limit {:.3g} x the run's step bound\n",
                         flat_hex, flat_hex_ratio, flat_hex_margin);
        if (!flat_hex_warning.empty()) s += "    " + flat_hex_warning + "\n";
    }
    s += fmt::format("  time step: first {:.4g} s, min {:.4g} s, max {:.4g} s; {} steps to t = {:.6g} s\n", first_dt,
                     min_dt, max_dt, steps, end_time);
    if (step_limits.size() > 1) {
        std::vector<std::string> limits;
        for (const auto& l : step_limits) limits.push_back(fmt::format("{} {:.4g} s", l.name, l.dt));
        s += fmt::format("  step limits at the end (1/dt^2 = sum of 1/dt_i^2, then the safety factor): {} -> {:.4g} s\n",
                         fmt::join(limits, ", "), step_at_end);
    }
    s += fmt::format("  energies [J]: kinetic {:.6g}, internal {:.6g}, hourglass {:.6g}, damping {:.6g}, "
                     "viscous {:.6g}, contact {:.6g}, external work {:.6g}, initial {:.6g}\n",
                     energy.kinetic, energy.internal, energy.hourglass, energy.damping, energy.viscous,
                     energy.contact, energy.external, energy.initial);
    const std::string window = std::isfinite(energy.window_until) || energy.window_from > 0.0
                                   ? fmt::format(" (judged window {:.6g} to {:.6g} s)", energy.window_from, energy.window_until)
                                   : "";
    s += fmt::format("  energy balance error: final {:.3g} J, max |error| {:.3g} J = {:.3g} of the largest total energy "
                     "{:.4g} J{}\n",
                     energy.balance_error, energy.max_abs_balance_error, energy.relative_error(), energy.reference, window);
    s += fmt::format("  hourglass energy: max {:.4g} J = {:.3g} of the max internal energy {:.4g} J\n",
                     energy.max_hourglass, energy.hourglass_fraction(), energy.max_internal);
    if (energy.parts.size() > 1)
        for (const auto& p : energy.parts)
            s += fmt::format("    part '{}': max {:.4g} J = {:.3g} of its max internal energy {:.4g} J\n", p.part,
                             p.max_hourglass, p.hourglass_fraction(), p.max_internal);
    s += fmt::format("  wall time {:.3f} s, {:.4g} element-cycles/s\n", wall_s, element_cycles_per_s);
    const auto row = [&](const char* what, double t) {
        return fmt::format("    {:<24} {:10.3f} {:7.1f} %\n", what, t, wall_s > 0 ? 100.0 * t / wall_s : 0.0);
    };
    s += fmt::format("  timing                     wall [s]   share\n");
    s += row("element forces", timing.elements);
    s += row("contact search", timing.contact_search);
    s += row("contact forces", timing.contact_forces);
    s += row("constraints, rigid parts", timing.constraints);
    s += row("node update", timing.update);
    s += row("output", timing.output);
    s += row("other", timing.other);
    s += fmt::format("    (the timers' own cost: about {:.3g} s, {} clock reads)\n", timing.timer_overhead,
                     timing.clock_reads);
    for (const auto& c : interfaces)
        s += fmt::format("  contact '{}': max penetration {:.4g} mm ({:.3g} of the slave element), energy {:.4g} J "
                         "(stored {:.4g}, dissipated {:.4g}), search {:.3f} s, forces {:.3f} s\n",
                         c.name, 1e3 * c.max_penetration, c.max_penetration_fraction, c.energy, c.stored_energy,
                         c.dissipated_energy, c.search_s, c.forces_s);
    return s;
}

nlohmann::json RunSummary::to_json() const {
    nlohmann::json interfaces_json = nlohmann::json::array();
    for (const auto& c : interfaces)
        interfaces_json.push_back({{"name", c.name},
                                   {"max_penetration_m", c.max_penetration},
                                   {"max_penetration_fraction", c.max_penetration_fraction},
                                   {"energy_J", c.energy},
                                   {"stored_energy_J", c.stored_energy},
                                   {"dissipated_energy_J", c.dissipated_energy},
                                   {"search_s", c.search_s},
                                   {"forces_s", c.forces_s}});
    nlohmann::json parts_json = nlohmann::json::array();
    for (const auto& p : energy.parts)
        parts_json.push_back({{"part", p.part},
                              {"max_internal_energy_J", p.max_internal},
                              {"max_hourglass_energy_J", p.max_hourglass},
                              {"hourglass_fraction_of_internal", p.hourglass_fraction()}});
    return {{"name", name},
            {"nodes", nodes},
            {"rotational_nodes", rotational_nodes},
            {"elements", elements},
            {"rigid_parts", rigid_parts},
            {"threads", threads},
            {"steps", steps},
            {"end_time_s", end_time},
            {"first_dt_s", first_dt},
            {"min_dt_s", min_dt},
            {"max_dt_s", max_dt},
            {"controlling_element",
             fmt::format("part '{}' block {} {} element {}", controlling_part, controlling_block, controlling_kind,
                         controlling_element)},
            {"controlling_dt_s", controlling_dt},
            {"controlling_rule", controlling_rule},
            {"step_limits_at_end_s", [&] {
                 nlohmann::json j = nlohmann::json::object();
                 for (const auto& l : step_limits) j[l.name] = l.dt;
                 return j;
             }()},
            {"step_at_end_s", step_at_end},
            {"stability_factor", stability_factor},
            {"flat_hex", flat_hex},
            // null, not 0, when no hexahedron is flat enough to name: a margin of 0 would read as "unstable now".
            {"flat_hex_ratio", flat_hex.empty() ? nlohmann::json(nullptr) : nlohmann::json(flat_hex_ratio)},
            {"flat_hex_margin", flat_hex.empty() ? nlohmann::json(nullptr) : nlohmann::json(flat_hex_margin)},
            {"mass_kg", mass},
            {"added_mass_kg", added_mass},
            {"added_mass_fraction", added_mass_fraction},
            {"energy_kinetic_J", energy.kinetic},
            {"energy_internal_J", energy.internal},
            {"energy_hourglass_J", energy.hourglass},
            {"energy_damping_J", energy.damping},
            {"energy_viscous_J", energy.viscous},
            {"external_work_J", energy.external},
            {"energy_contact_J", energy.contact},
            {"energy_balance_relative_error", energy.relative_error()},
            {"hourglass_fraction_of_internal", energy.hourglass_fraction()},
            {"energy_scale_J", energy.reference},
            {"health_window_s", {energy.window_from, std::min(energy.window_until, end_time)}},
            {"parts", parts_json},
            {"wall_s", wall_s},
            {"element_cycles_per_s", element_cycles_per_s},
            {"timing_s",
             {{"elements", timing.elements},
              {"contact_search", timing.contact_search},
              {"contact_forces", timing.contact_forces},
              {"constraints", timing.constraints},
              {"update", timing.update},
              {"output", timing.output},
              {"other", timing.other},
              {"timers_own_cost", timing.timer_overhead}}},
            {"contact_share", wall_s > 0 ? (timing.contact_search + timing.contact_forces) / wall_s : 0.0},
            {"contact_interfaces", interfaces_json}};
}

void RunSummary::erase_machine_facts(nlohmann::json& summary) {
    for (const char* key : {"wall_s", "element_cycles_per_s", "threads", "timing_s", "contact_share"}) summary.erase(key);
    if (summary.contains("contact_interfaces"))
        for (auto& c : summary["contact_interfaces"]) c.erase("search_s"), c.erase("forces_s");
}

// ===================================================================================================
// ExplicitSolver
// ===================================================================================================

ExplicitSolver::ExplicitSolver(ExplicitModel& model, ExplicitOptions options)
    : model_(model), opt_(std::move(options)) {
    if (!(opt_.end_time > 0.0)) throw InputError(fmt::format("explicit run '{}': end_time must be > 0", opt_.name));
    if (!(opt_.dt_scale > 0.0 && opt_.dt_scale <= 1.0))
        throw InputError(fmt::format("explicit run '{}': dt_scale {} must be in (0, 1]", opt_.name, opt_.dt_scale));
    if (opt_.dt_interval < 1) throw InputError("dt_interval must be >= 1");
    if (opt_.fixed_dt < 0 || opt_.mass_scaling_dt < 0 || opt_.history_interval < 0 || opt_.vtu_interval < 0 ||
        opt_.restart_interval < 0)
        throw InputError(fmt::format("explicit run '{}': negative fixed_dt, mass_scaling_dt or interval", opt_.name));
    if ((opt_.restart_interval > 0 || !opt_.restart_times.empty()) && opt_.restart_dir.empty())
        throw InputError(fmt::format("explicit run '{}': restart dumps asked for (restart_times or restart_interval) "
                                     "but no restart_dir",
                                     opt_.name));
    if (!(opt_.health_from >= 0.0 && opt_.health_until > opt_.health_from))
        throw InputError(fmt::format("explicit run '{}': the judged window [{}, {}] s (health_from, health_until) is empty",
                                     opt_.name, opt_.health_from, opt_.health_until));
    initialize();
}

ExplicitSolver::~ExplicitSolver() = default;

std::string ExplicitSolver::element_name(int g, int e) const {
    if (g < 0) return "no element";
    const auto& grp = *model_.groups()[g];
    if (grp.block < 0) return fmt::format("part '{}' {} {}", grp.part, grp.kind(), e + 1);  // point masses added one by one
    return block_element_name(grp.block, e);
}

std::string ExplicitSolver::block_element_name(int b, int e) const {
    // The element's number in the user's file (Gmsh tag, deck number; ElementBlock::ids), and the
    // block when a part has several generated blocks (their numbers restart at 1 in each).
    const Mesh& mesh = model_.mesh();
    const ElementBlock& blk = mesh.blocks[b];
    std::string s = fmt::format("part '{}' {} element {}", blk.part, to_string(blk.shape), blk.id(e));
    if (blk.ids.empty() && mesh.blocks_of_part(blk.part).size() > 1) s += fmt::format(" of block {}", b);
    return s;
}

void ExplicitSolver::initialize() {
    model_.finalize();
    const Mesh& mesh = model_.mesh();
    const int n = mesh.node_count();
    auto& groups = model_.groups();
    s_.X = mesh.nodes;
    s_.x = mesh.nodes;
    s_.v = model_.initial_velocity().empty() ? std::vector<Vec3>(n, Vec3::Zero()) : model_.initial_velocity();
    s_.f.assign(n, Vec3::Zero());
    s_.mass.assign(n, 0.0);
    s_.rot_index.assign(n, -1);
    for (const auto& g : groups)
        if (g->needs_rotations())
            for (int node : g->nodes())
                if (s_.rot_index[node] < 0) {
                    s_.rot_index[node] = static_cast<int>(s_.rot_node.size());
                    s_.rot_node.push_back(node);
                }
    const int nr = s_.rotational_count();
    s_.omega.assign(nr, Vec3::Zero());
    s_.moment.assign(nr, Vec3::Zero());
    s_.inertia.assign(nr, 0.0);
    s_.rotation.assign(nr, Mat3::Identity());
    for (const auto& [node, w] : model_.initial_angular_velocity()) {
        if (s_.rot_index[node] < 0)
            throw InputError(fmt::format("initial angular velocity on node {}, which has no rotations (no beam or shell)", node));
        s_.omega[s_.rot_index[node]] = w;
    }

    // Selective mass scaling (Sec 2.3.5, observation 4): raise every element's critical step to
    // mass_scaling_dt / dt_scale by scaling its density with (dt_target / dt_e)^2.
    summary_ = RunSummary{};
    summary_.energy.window_from = opt_.health_from;  // the judged window (EnergySummary)
    summary_.energy.window_until = opt_.health_until;
    summary_.name = opt_.name;
    // Also the smallest Table 2-1 step of the solid groups on the reference (with the scaling), the
    // step the measured stability factor refers to (measure_omega_max).
    double solid_table_dt = std::numeric_limits<double>::infinity();
    solid_.assign(groups.size(), 0);
    dt_factor_.assign(groups.size(), 1.0);
    // Parts for the per-part energies (EnergySummary::parts), in the order of their first group.
    group_part_.assign(groups.size(), -1);
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        auto& parts = summary_.energy.parts;
        const auto it = std::find_if(parts.begin(), parts.end(), [&](const PartEnergy& p) { return p.part == groups[gi]->part; });
        group_part_[gi] = static_cast<int>(it - parts.begin());
        if (it == parts.end()) parts.push_back({groups[gi]->part});
    }
    part_int_.assign(summary_.energy.parts.size(), 0.0);
    part_hg_.assign(summary_.energy.parts.size(), 0.0);
    // Each solid element's Table 2-1 step on the reference, with its mass scaling, and the same in
    // compression (the bulk viscosity's C1 term, Q = C1 c): the flat-hexahedron survey below.
    std::vector<std::vector<double>> scaled_ref(groups.size());
    double compressed_table_dt = std::numeric_limits<double>::infinity();
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        auto& g = groups[gi];
        const std::vector<double> ref = g->reference_time_steps();
        std::vector<double> f(ref.size(), 1.0);
        if (opt_.mass_scaling_dt > 0.0) {
            const double target = opt_.mass_scaling_dt / opt_.dt_scale;
            for (std::size_t e = 0; e < ref.size(); ++e)
                if (std::isfinite(ref[e])) f[e] = cfl::density_scale_for_time_step(ref[e], target);
            g->set_mass_scaling(f);
        }
        // Solid: no rotational DOFs and a critical step (hexahedra, tetrahedra; not beams, point masses).
        if (!g->needs_rotations()) {
            const double compression = cfl::compression_step_factor(g->bulk_viscosity_linear());
            scaled_ref[gi].assign(ref.size(), std::numeric_limits<double>::infinity());
            for (std::size_t e = 0; e < ref.size(); ++e)
                if (std::isfinite(ref[e])) {
                    solid_[gi] = 1;
                    scaled_ref[gi][e] = ref[e] * std::sqrt(f[e]);
                    solid_table_dt = std::min(solid_table_dt, scaled_ref[gi][e]);
                    compressed_table_dt = std::min(compressed_table_dt, scaled_ref[gi][e] * compression);
                }
        }
    }
    // The hexahedron with bulk viscosity nearest its damped step limit (README "Flat hexahedra and
    // bulk viscosity"): where cbrt(V) > 2 V / A_max the viscosity takes more of the step than Table 2-1
    // allows for, by cfl::flat_hexahedron_step_factor. Its margin is its damped limit over the run's
    // step bound in compression (dt_scale x the smallest compressed Table 2-1 step, or the fixed step);
    // below 1 the run is likely to go unstable within tens of cycles.
    const double step_bound = opt_.fixed_dt > 0.0 ? opt_.fixed_dt : opt_.dt_scale * compressed_table_dt;
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        const auto& g = groups[gi];
        const double c1 = g->bulk_viscosity_linear();
        if (g->block < 0 || model_.mesh().blocks[g->block].shape != ElementShape::Hex8 || !(c1 > 0.0)) continue;
        const ElementBlock& blk = model_.mesh().blocks[g->block];
        for (int e = 0; e < blk.size(); ++e) {
            std::array<Vec3, 8> X;
            const auto conn = blk.element(e);
            for (int a = 0; a < 8; ++a) X[a] = s_.X[conn[a]];
            const double r = hex_lengths(X).ratio();
            if (!(r > 2.0)) continue;
            const double limit = cfl::flat_hexahedron_step_factor(r, c1) * scaled_ref[gi][e] * cfl::compression_step_factor(c1);
            const double margin = limit / step_bound;
            if (summary_.flat_hex.empty() || margin < summary_.flat_hex_margin) {
                summary_.flat_hex_ratio = r;
                summary_.flat_hex_margin = margin;
                summary_.flat_hex = block_element_name(g->block, e);
            }
        }
    }
    if (!summary_.flat_hex.empty() && summary_.flat_hex_margin < kFlatHexWarnMargin) {
        const double safe = summary_.flat_hex_margin / kFlatHexWarnMargin;
        summary_.flat_hex_warning = fmt::format(
            "WARNING: the run's step bound is {:.3f} x the damped step limit of {} (cbrt(V) = {:.3g} x V / A_max; warned "
            "from {:.3f}, the model's accuracy): it may go unstable; {} or lower the part's bulk_linear "
            "(lib/explicit/README.md, \"Flat hexahedra and bulk viscosity\")",
            1.0 / summary_.flat_hex_margin, summary_.flat_hex, summary_.flat_hex_ratio, 1.0 / kFlatHexWarnMargin,
            opt_.fixed_dt > 0.0 ? fmt::format("use a fixed step below {:.4g} s", opt_.fixed_dt * safe)
                                : fmt::format("use dt_scale below {:.3g}", opt_.dt_scale * safe));
        std::cerr << fmt::format("explicit run '{}': {}\n", opt_.name, summary_.flat_hex_warning);
    }
    for (const auto& g : groups) {
        g->initialize(s_);  // history variables (shell stresses) start from this state
        summary_.added_mass += g->add_lumped_mass(s_);
        summary_.mass += g->mass();
        summary_.elements += g->size();
    }
    summary_.added_mass_fraction = summary_.mass > 0 ? summary_.added_mass / summary_.mass : 0.0;
    summary_.nodes = n;
    summary_.rotational_nodes = nr;
    for (int k = 0; k < nr; ++k)
        if (!(s_.inertia[k] > 0.0))
            throw InputError(fmt::format("node {} has rotations but no rotational inertia", s_.rot_node[k]));

    // Damping per node: the largest alpha of the parts the node belongs to.
    alpha_.assign(n, model_.global_mass_damping());
    for (const auto& [part, a] : model_.mass_damping()) {
        bool found = false;
        for (const auto& g : groups)
            if (g->part == part) {
                found = true;
                for (int node : g->nodes()) alpha_[node] = std::max(alpha_[node], a);
            }
        if (!found) throw InputError(fmt::format("mass damping given for part '{}', which the model does not have", part));
    }
    alpha_rot_.resize(nr);
    for (int k = 0; k < nr; ++k) alpha_rot_[k] = alpha_[s_.rot_node[k]];

    // Constraints.
    fixed_ = model_.fixed();
    target_index_.assign(n, -1);
    for (const auto& p : model_.prescribed())
        for (int node : p.nodes)
            if (target_index_[node] < 0) {
                target_index_[node] = static_cast<int>(target_.size());
                const double nan = std::numeric_limits<double>::quiet_NaN();
                target_.push_back({nan, nan, nan});
            }
    // A node follows one motion at most; the motion overrides fix() on its translations.
    std::vector<int> motion_of(n, -1);
    for (int k = 0; k < static_cast<int>(model_.motions().size()); ++k) {
        const auto& mo = model_.motions()[k];
        for (int node : mo.nodes) {
            if (motion_of[node] >= 0 && motion_of[node] != k) {
                auto what = [&](int m) {
                    const auto& p = model_.motions()[m].part;
                    return p.empty() ? std::string("a prescribed motion") : fmt::format("rigid part '{}'", p);
                };
                throw InputError(fmt::format("node {} follows two motions: {} and {}", node, what(motion_of[node]),
                                             what(k)));
            }
            motion_of[node] = k;
            fixed_[node] &= ~7u;
            if (target_index_[node] < 0) {
                target_index_[node] = static_cast<int>(target_.size());
                const double nan = std::numeric_limits<double>::quiet_NaN();
                target_.push_back({nan, nan, nan});
            }
        }
        if (!mo.part.empty()) summary_.rigid_parts.push_back(mo.part);
    }
    for (const auto& l : model_.loads()) {
        has_loads_ = true;
        if (l.moment)
            for (int node : l.nodes)
                if (s_.rot_index[node] < 0)
                    throw InputError(fmt::format("nodal moment on node {}, which has no rotations (no beam or shell)", node));
    }
    if (model_.gravity().squaredNorm() > 0) has_loads_ = true;
    fext_.assign(n, Vec3::Zero());
    mext_.assign(nr, Vec3::Zero());
    // Viscous nodal forces, only when a group books them (see the update loop in run()).
    book_viscous_ = false;
    for (const auto& g : groups) book_viscous_ = book_viscous_ || (opt_.exact_viscous_energy && g->adds_viscous_forces());
    if (book_viscous_) s_.fv.assign(n, Vec3::Zero());
    if (!model_.force_providers().empty()) {
        fprov_.assign(n, Vec3::Zero());
        mprov_.assign(nr, Vec3::Zero());
        for (auto& p : model_.force_providers()) p->initialize(s_);
    }
    for (int i = 0; i < n; ++i) {
        for (int d = 0; d < 3; ++d)
            if ((fixed_[i] >> d) & 1u) s_.v[i][d] = 0.0;
    }
    for (int k = 0; k < nr; ++k)
        for (int d = 0; d < 3; ++d)
            if ((fixed_[s_.rot_node[k]] >> (d + 3)) & 1u) s_.omega[k][d] = 0.0;

    // History set-up.
    history_ = History{};
    for (const auto& h : opt_.history_nodes) {
        if (h.node < 0 || h.node >= n)
            throw InputError(fmt::format("history node '{}': node {} out of range ({} nodes)", h.name, h.node, n));
        history_.nodes.push_back({h.name, h.node, {}, {}});
    }
    if (!opt_.pvd_path.empty()) pvd_ = std::make_unique<io::PvdSeries>(opt_.pvd_path);

    t_ = 0.0;
    step_ = 0;
    if (!opt_.restart_from.empty()) {
        restore(opt_.restart_from);
    } else {
        start_fresh(solid_table_dt);
    }
    // Restart dumps still to come.
    restart_times_.clear();
    for (double t : opt_.restart_times)
        if (t > t_) restart_times_.push_back(t);
    std::sort(restart_times_.begin(), restart_times_.end());
    next_restart_ = t_ + opt_.restart_interval;
}

namespace {
// Hands the measured stability factor r to the solid groups (solid[gi] != 0). Groups that can
// apply r themselves do so before their stiffness-damping reduction (set_stability_factor;
// tetrahedra, whose reference steps are element bounds, take r > 1 too): marked solid[gi] = 2.
// For the others the solver multiplies their step by r, at most 1 (dt_factor): their Table 2-1
// steps are not bounds, and a factor above 1 on them is backed by nothing once the mesh deforms.
void apply_stability_factor(std::vector<std::unique_ptr<ElementGroup>>& groups, double r, std::vector<char>& solid,
                            std::vector<double>& dt_factor) {
    for (std::size_t gi = 0; gi < groups.size(); ++gi)  // (also resets a factor left by an earlier solver)
        if (solid[gi]) {
            solid[gi] = groups[gi]->set_stability_factor(r) ? 2 : 1;
            dt_factor[gi] = solid[gi] == 2 ? 1.0 : std::min(1.0, r);
        }
}
}  // namespace

void ExplicitSolver::start_fresh(double solid_table_dt) {
    const int n = s_.node_count(), nr = s_.rotational_count();
    auto& groups = model_.groups();
    // Forces and critical step at t = 0.
    // One stability factor for all solid groups (hexahedra and tetrahedra alike): the measured
    // omega_max is that of the assembled solid model (shared nodes couple the groups' frequencies, so
    // only the assembled measurement is exact; per-group measurements are bounds only with each
    // group's own masses, free-free), and r = (2/omega_max) / (smallest reference step of the solid
    // elements) makes the smallest scaled step exactly 2/omega_max at rest. Beams and point masses
    // keep their own steps.
    if (opt_.hex_stability_check) {
        omega_max_ = measure_omega_max();
        if (omega_max_ > 0.0 && std::isfinite(solid_table_dt)) stability_factor_ = (2.0 / omega_max_) / solid_table_dt;
    }
    apply_stability_factor(groups, stability_factor_, solid_, dt_factor_);
    compute_forces(true);
    summary_.stability_factor = stability_factor_;
    if (opt_.fixed_dt > 0.0 && opt_.fixed_dt > dt_crit_ && !opt_.allow_unstable_fixed_dt)
        throw InputError(fmt::format("explicit run '{}': the requested time step {:.4g} s is above the critical step "
                                     "{:.4g} s of {} (Table 2-1{}); use at most {:.4g} s (0.9 x critical, Eq 2-27) or "
                                     "mass scaling",
                                     opt_.name, opt_.fixed_dt, dt_crit_, element_name(dt_group_, dt_element_),
                                     stability_factor_ < 1.0 ? fmt::format(" x measured factor {:.4f}", stability_factor_) : "",
                                     opt_.dt_scale * dt_crit_));
    summary_.controlling_dt = dt_crit_unscaled_;
    double ke0 = 0.0;
    for (int i = 0; i < n; ++i) ke0 += 0.5 * s_.mass[i] * s_.v[i].squaredNorm();
    for (int k = 0; k < nr; ++k) ke0 += 0.5 * s_.inertia[k] * s_.omega[k].squaredNorm();
    e_kin_ = ke0;
    e0_ = ke0 + e_int_ + e_hg_;
    input_scale_ = std::abs(e0_);
}

namespace {
// y = M^-1/2 K M^-1/2 x over the free translational DOFs of the solid groups, K applied matrix-free
// as the change of the groups' internal forces for a tiny displacement from the reference state
// (at rest, zero velocity: the elements are linear there, viscous terms vanish), so Lanczos finds
// omega_max^2. Any group works: only ElementGroup::internal_forces is used.
class SolidStiffnessOp {
public:
    using Scalar = double;
    SolidStiffnessOp(NodalState& s, std::vector<ElementGroup*> groups, std::vector<std::pair<int, int>> dofs, double h)
        : s_(s), groups_(std::move(groups)), dofs_(std::move(dofs)), h_(h) {}
    int rows() const { return static_cast<int>(dofs_.size()); }
    int cols() const { return rows(); }
    void perform_op(const double* x, double* y) const {
        double mx = 0.0;
        for (int i = 0; i < rows(); ++i) mx = std::max(mx, std::abs(x[i]) / std::sqrt(s_.mass[dofs_[i].first]));
        for (int i = 0; i < s_.node_count(); ++i) {
            s_.x[i] = s_.X[i];
            s_.f[i].setZero();
        }
        if (mx == 0.0) {
            std::fill(y, y + rows(), 0.0);
            return;
        }
        const double eps = 1e-7 * h_ / mx;  // largest nodal displacement 1e-7 element sizes
        for (int i = 0; i < rows(); ++i) {
            const auto [n, d] = dofs_[i];
            s_.x[n][d] += eps * x[i] / std::sqrt(s_.mass[n]);
        }
        for (auto* g : groups_) g->internal_forces(s_, false);
        for (int i = 0; i < rows(); ++i) {
            const auto [n, d] = dofs_[i];
            y[i] = s_.f[n][d] / (eps * std::sqrt(s_.mass[n]));
        }
    }

private:
    NodalState& s_;
    std::vector<ElementGroup*> groups_;
    std::vector<std::pair<int, int>> dofs_;
    double h_;
};

// omega_max of one free cube of side h (the worst hexahedron: every node a corner), the closed form
// sqrt((3 lambda + 2 mu) / rho) 2/h: an element bound for Hex8Group (which does not provide
// element_omega_bound itself).
double hex_element_omega_bound(const Hex8Group& g) {
    const auto& m = g.material();
    double w = 0.0;
    for (int e = 0; e < g.size(); ++e)
        w = std::max(w, 2.0 * std::sqrt((3.0 * m.lame_lambda() + 2.0 * m.shear_modulus()) / m.density) /
                            std::cbrt(g.reference(e).volume));
    return w;
}
}  // namespace

double ExplicitSolver::measure_omega_max() {
    std::vector<ElementGroup*> solids;
    std::vector<char> used(s_.node_count(), 0);
    for (std::size_t gi = 0; gi < model_.groups().size(); ++gi)
        if (solid_[gi]) {
            solids.push_back(model_.groups()[gi].get());
            for (int n : solids.back()->nodes()) used[n] = 1;
        }
    if (solids.empty()) return 0.0;
    std::vector<std::pair<int, int>> dofs;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int n = 0; n < s_.node_count(); ++n)
        if (used[n] && s_.mass[n] > 0.0) {
            lo = lo.cwiseMin(s_.X[n]);
            hi = hi.cwiseMax(s_.X[n]);
            for (int d = 0; d < 3; ++d)
                if (!((fixed_[n] >> d) & 1u) && !(target_index_[n] >= 0)) dofs.push_back({n, d});
        }
    const int n = static_cast<int>(dofs.size());
    if (n < 3) return 0.0;
    // A typical element size for the perturbation (the model's extent over the cube root of its node
    // count): linearity needs it small against every element, precision large against round-off of
    // the coordinates; 1e-7 of it is both for any practical grading.
    const double h = (hi - lo).norm() / std::cbrt(static_cast<double>(n / 3 + 1));
    NodalState tmp = s_;
    for (auto& v : tmp.v) v.setZero();
    tmp.fv.clear();  // nothing to book here
    SolidStiffnessOp op(tmp, solids, dofs, h);
    // Ritz value theta: the residual bound puts an eigenvalue within tol theta of it, so
    // lambda_max <= theta (1 + tol) once Lanczos has found the top of the spectrum.
    const double tol = 1e-6;
    Spectra::SymEigsSolver<SolidStiffnessOp> eigs(op, 1, std::min(n, 40));
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, 2000, tol);
    if (eigs.info() == Spectra::CompInfo::Successful && eigs.eigenvalues()[0] > 0.0)
        return std::sqrt(eigs.eigenvalues()[0] * (1.0 + tol));
    // Not converged: the element eigenvalue inequality (omega_max <= the largest element omega, each
    // element alone with its lumped masses) gives a guaranteed, pessimistic bound.
    double w = 0.0;
    for (auto* g : solids) {
        const auto* hex = dynamic_cast<const Hex8Group*>(g);
        const double wg = hex ? hex_element_omega_bound(*hex) : g->element_omega_bound();
        if (!(wg > 0.0))
            throw SolverError(fmt::format("explicit run '{}': the stability measurement (Lanczos) did not converge and "
                                          "part '{}' ({}) gives no element bound; set hex_stability_check = false "
                                          "and a safe fixed_dt",
                                          opt_.name, g->part, g->kind()));
        w = std::max(w, wg);
    }
    std::fprintf(stderr, "explicit run '%s': stability measurement did not converge; element bound used\n",
                 opt_.name.c_str());
    return w;
}

void ExplicitSolver::compute_forces(bool compute_dt) {
    const int n = s_.node_count();
    par::for_each_index(n, n >= par::kParallelMin, [&](int i) { s_.f[i].setZero(); });
    for (auto& m : s_.moment) m.setZero();
    if (book_viscous_) par::for_each_index(n, n >= par::kParallelMin, [&](int i) { s_.fv[i].setZero(); });
    e_int_ = e_hg_ = visc_power_ = 0.0;
    std::fill(part_int_.begin(), part_int_.end(), 0.0);
    std::fill(part_hg_.begin(), part_hg_.end(), 0.0);
    group_vm_.resize(model_.groups().size());
    double dt = std::numeric_limits<double>::infinity();
    int dg = -1, de = -1;
    auto& groups = model_.groups();
    for (int g = 0; g < static_cast<int>(groups.size()); ++g) {
        const GroupForceResult r = groups[g]->internal_forces(s_, compute_dt);
        element_cycles_ += groups[g]->size();
        if (r.bad_element >= 0)
            unstable("an element inverted or its state became non-finite", g, r.bad_element);
        e_int_ += r.internal_energy;
        e_hg_ += r.hourglass_energy;
        part_int_[group_part_[g]] += r.internal_energy;
        part_hg_[group_part_[g]] += r.hourglass_energy;
        // Groups that add their viscous forces to s_.fv are booked in the update loop instead.
        if (!(book_viscous_ && groups[g]->adds_viscous_forces())) visc_power_ += r.viscous_power;
        double& vm = max_vm_[groups[g]->part];
        vm = std::max(vm, r.max_von_mises);
        group_vm_[g] = r.max_von_mises;
        if (compute_dt && dt_factor_[g] * r.dt_min < dt) {
            dt = dt_factor_[g] * r.dt_min;
            dg = g;
            de = r.dt_element;
        }
    }
    if (compute_dt) {
        if (!std::isfinite(dt))
            throw InputError(fmt::format("explicit run '{}': no element limits the time step (only point masses?)",
                                         opt_.name));
        dt_crit_ = dt;
        // Before the stability factor (the summary's controlling step), whoever applied it.
        dt_crit_unscaled_ = solid_[dg] == 2 ? dt / stability_factor_ : solid_[dg] ? dt / dt_factor_[dg] : dt;
        dt_group_ = dg;
        dt_element_ = de;
    }
}

void ExplicitSolver::external_forces(double t) {
    if (!has_loads_) return;
    // Gravity alone (no point loads): fext = m g c(t) changes only when the curve value c does
    // (a ramp, a switch-on); while it holds, the last cycle's fext_ is what this pass would write
    // again, bit for bit, so it is kept (a full pass over the nodes per cycle saved: 1.7 % of the
    // football sweep's samples).
    if (model_.loads().empty()) {
        const double c = model_.gravity_curve()(t);
        if (c == gravity_c_ && !std::signbit(c) == !std::signbit(gravity_c_)) return;
        gravity_c_ = c;
    }
    for (auto& f : fext_) f.setZero();
    for (auto& m : mext_) m.setZero();
    for (const auto& l : model_.loads()) {
        const Vec3 v = l.value * l.curve(t);
        for (int node : l.nodes) {
            if (l.moment)
                mext_[s_.rot_index[node]] += v;
            else
                fext_[node] += v;
        }
    }
    if (model_.gravity().squaredNorm() > 0) {
        const double c = model_.gravity_curve()(t);
        if (c != 0.0) {
            const Vec3 g = model_.gravity() * c;
            for (int i = 0; i < s_.node_count(); ++i) fext_[i] += s_.mass[i] * g;
        }
    }
}

void ExplicitSolver::unstable(const std::string& why, int bad_group, int bad_element) {
    // Where: the element found bad, else the element around the node with the largest kinetic
    // energy (where a numerical instability grows fastest) that is compressed most.
    const Mesh& mesh = model_.mesh();
    int worst = -1;
    double ew = -1.0;
    for (int i = 0; i < s_.node_count(); ++i) {
        const double e = s_.mass[i] * s_.v[i].squaredNorm();
        if (!std::isfinite(e)) {
            worst = i;
            break;
        }
        if (e > ew) {
            ew = e;
            worst = i;
        }
    }
    // Current over initial centre Jacobian of a solid (<= 0: inverted); 1 for other shapes.
    const auto volume_ratio = [&](int b, int e) {
        const ElementBlock& blk = mesh.blocks[b];
        std::vector<Vec3> x, X;
        for (int n : blk.element(e)) {
            x.push_back(s_.x[n]);
            X.push_back(s_.X[n]);
        }
        const double j0 = centre_jacobian(blk.shape, X);
        return j0 > 0.0 ? centre_jacobian(blk.shape, x) / j0 : 1.0;
    };
    int block = bad_group >= 0 ? model_.groups()[bad_group]->block : -1, element = bad_element;
    if (block < 0) {
        double least = std::numeric_limits<double>::infinity();
        for (const auto& g : model_.groups())
            if (g->block >= 0 && worst >= 0)
                for (int e = 0; e < mesh.blocks[g->block].size(); ++e) {
                    const auto conn = mesh.blocks[g->block].element(e);
                    if (std::find(conn.begin(), conn.end(), worst) == conn.end()) continue;
                    const double r = volume_ratio(g->block, e);
                    if (!(r >= least)) {  // (NaN first)
                        least = r;
                        block = g->block;
                        element = e;
                    }
                }
    }
    std::string place = "no element", cause;
    const double ratio = block >= 0 ? volume_ratio(block, element) : 1.0;
    if (block >= 0) {
        Vec3 centre = Vec3::Zero();
        for (int n : mesh.blocks[block].element(element)) centre += s_.X[n];
        centre /= mesh.blocks[block].nodes_per_element();
        place = fmt::format("{} (initially centred at {:.4g}, {:.4g}, {:.4g})", block_element_name(block, element),
                            centre.x(), centre.y(), centre.z());
    }
    // A flat hexahedron with bulk viscosity: the viscosity's pressure acts over the cube root of the
    // element's volume (LS-DYNA's length for solids), while its Table 2-1 step allows for damping over
    // the step's own length V / A_max only; far apart, the step leaves no room for that damping
    // (README "Flat hexahedra and bulk viscosity": a bar of 1.25 x 20 x 20 mm elements at dt_scale 0.9).
    HexLengths lengths;
    double damped_factor = 1.0;  // its damped step limit over its Table 2-1 step (cfl::flat_hexahedron_step_factor)
    if (block >= 0 && mesh.blocks[block].shape == ElementShape::Hex8) {
        double c1 = 0.0;
        for (const auto& g : model_.groups())
            if (g->block == block) c1 = g->bulk_viscosity_linear();
        std::array<Vec3, 8> X;
        const auto conn = mesh.blocks[block].element(element);
        for (int a = 0; a < 8; ++a) X[a] = s_.X[conn[a]];
        lengths = hex_lengths(X);
        if (c1 > 0.0) damped_factor = cfl::flat_hexahedron_step_factor(lengths.ratio(), c1);
    }
    // Why, most likely: a fixed step above the critical one (Eq 2-27), else a deformation the mesh
    // cannot follow: an inverted element, or elements collapsing faster than the step adapts.
    const double dt_used = dt_half_ > 0.0 ? dt_half_ : (opt_.fixed_dt > 0 ? opt_.fixed_dt : opt_.dt_scale * dt_crit_);
    const bool above = dt_used > dt_crit_ * (1.0 + 1e-9);
    const char* too_large = "a load, prescribed motion or contact too large for the mesh";
    if (above && opt_.fixed_dt > 0)
        cause = fmt::format("the fixed time step {:.4g} s is above the critical step {:.4g} s of {} (Eq 2-27); lower it "
                            "or use mass scaling", dt_used, dt_crit_, element_name(dt_group_, dt_element_));
    else if (!(ratio > 0.0))
        cause = fmt::format("the element inverted (its volume at the centre went through zero): {}", too_large);
    else if (above)
        cause = fmt::format("the critical step fell below the step in use ({:.4g} < {:.4g} s, {}): elements collapsing "
                            "faster than the step adapts, {}", dt_crit_, dt_used, element_name(dt_group_, dt_element_),
                            too_large);
    else if (damped_factor < 1.0 && damped_factor < 1.05 * dt_used / dt_crit_ && ratio > 0.9 && ratio < 1.1)
        // Its damped limit (at most, when it controls the step) within 5 % of the step in use: the
        // README's map of flat bars puts every unstable case there.
        cause = fmt::format("a flat element with bulk viscosity: the viscosity acts over the cube root of its volume, "
                            "{:.3g} m, {:.3g} x the length V / A_max = {:.3g} m its Table 2-1 step is taken over, which "
                            "makes its stable step {:.3g} x Table 2-1's while the step in use is {:.3g} x the critical "
                            "one (the element's volume is {:.3g} x its initial one: no large deformation); lower the "
                            "step scale (fem-explicit: [control] dt_scale) or the part's bulk_linear, or use less flat "
                            "elements",
                            lengths.viscous, lengths.ratio(), lengths.step, damped_factor, dt_used / dt_crit_, ratio);
    else
        cause = fmt::format("a deformation the mesh cannot follow (the element's volume is now {:.3g} x its initial "
                            "one): {}", ratio, too_large);
    throw SolverError(fmt::format(
        "explicit run '{}' went unstable at t = {:.6g} s (cycle {}) in {}: {}. Likely cause: {}. Step used {:.4g} s, "
        "critical step {:.4g} s ({}); largest kinetic energy at the node initially at {:.4g}, {:.4g}, {:.4g}",
        opt_.name, t_, step_, place, why, cause, dt_used, dt_crit_, element_name(dt_group_, dt_element_),
        worst >= 0 ? s_.X[worst].x() : 0.0, worst >= 0 ? s_.X[worst].y() : 0.0, worst >= 0 ? s_.X[worst].z() : 0.0));
}

void ExplicitSolver::record(bool force) {
    if (!force && t_ + 1e-12 * opt_.end_time < next_history_) return;
    next_history_ = t_ + opt_.history_interval;
    history_.time.push_back(t_);
    for (auto& h : history_.nodes) {
        h.displacement.push_back(s_.x[h.node] - s_.X[h.node]);
        h.velocity.push_back(s_.v[h.node]);
    }
    const EnergySummary& e = summary_.energy;
    history_.kinetic.push_back(e.kinetic);
    history_.internal.push_back(e.internal);
    history_.hourglass.push_back(e.hourglass);
    history_.damping.push_back(e.damping);
    history_.viscous.push_back(e.viscous);
    history_.external.push_back(e.external);
    history_.contact.push_back(e.contact);
    history_.balance.push_back(e.balance_error);
    for (auto& [part, vm] : max_vm_) {
        history_.max_von_mises[part].push_back(vm);
        vm = 0.0;
    }
    if (observer && opt_.observer_interval < 0.0) {
        last_observer_ = t_;
        observer(*this);
    }
}

void ExplicitSolver::notify_observer(bool force) {
    if (!observer || opt_.observer_interval < 0.0) return;
    if (!force && t_ + 1e-12 * opt_.end_time < next_observer_) return;
    next_observer_ = t_ + opt_.observer_interval;
    last_observer_ = t_;
    observer(*this);
}

double ExplicitSolver::max_von_mises(std::string_view part) const {
    double vm = 0.0;
    const auto& groups = model_.groups();
    for (std::size_t g = 0; g < groups.size() && g < group_vm_.size(); ++g)
        if (groups[g]->part == part) vm = std::max(vm, group_vm_[g]);
    return vm;
}

void ExplicitSolver::write_vtu(double t) {
    if (!pvd_ || t_ + 1e-12 * opt_.end_time < next_vtu_) return;
    next_vtu_ = t_ + opt_.vtu_interval;
    io::VtuData data;
    io::Field u{"displacement", 3, {}}, v{"velocity", 3, {}};
    for (int i = 0; i < s_.node_count(); ++i)
        for (int d = 0; d < 3; ++d) {
            u.values.push_back(s_.x[i][d] - s_.X[i][d]);
            v.values.push_back(s_.v[i][d]);
        }
    data.point_fields = {std::move(u), std::move(v)};
    // The force providers' nodal fields (contact pressure), summed over providers by name.
    std::map<std::string, std::vector<double>> nodal;
    for (const auto& p : model_.force_providers())
        for (auto& [name, values] : p->point_fields(s_)) {
            auto& sum = nodal[name];
            if (sum.empty()) sum.assign(s_.node_count(), 0.0);
            for (int i = 0; i < s_.node_count(); ++i) sum[i] += values[i];
        }
    for (auto& [name, values] : nodal) data.point_fields.push_back({name, 1, std::move(values)});
    // One stress per element, in block order (blocks without a group: zero).
    const Mesh& mesh = model_.mesh();
    std::vector<std::vector<double>> per_block(mesh.blocks.size());
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b) per_block[b].assign(mesh.blocks[b].size(), 0.0);
    for (const auto& g : model_.groups())
        if (g->block >= 0) per_block[g->block] = g->element_stress();
    io::Field vm{"von_mises", 1, {}};
    for (const auto& b : per_block) vm.values.insert(vm.values.end(), b.begin(), b.end());
    data.cell_fields = {std::move(vm)};
    // The groups' further fields (shells: von Mises at the bottom, mid and top surfaces), zero on
    // the blocks of groups that do not have them.
    std::map<std::string, std::vector<std::vector<double>>> extra;
    for (const auto& g : model_.groups())
        for (auto& [name, values] : g->cell_fields()) {
            auto& blocks = extra[name];
            if (blocks.empty())
                for (std::size_t b = 0; b < mesh.blocks.size(); ++b) blocks.emplace_back(mesh.blocks[b].size(), 0.0);
            if (g->block >= 0) blocks[g->block] = std::move(values);
        }
    for (auto& [name, blocks] : extra) {
        io::Field f{name, 1, {}};
        for (const auto& b : blocks) f.values.insert(f.values.end(), b.begin(), b.end());
        data.cell_fields.push_back(std::move(f));
    }
    pvd_->add(t, mesh, data, s_.x);
}

// ===================================================================================================
// Restart (ExplicitOptions::restart_*): the complete state a later cycle depends on, to HDF5 and back
// ===================================================================================================

namespace {
constexpr const char* kRestartFormat = "fem explicit restart 1";

// A run's name as the start of its restart files' names ("explicit" for an unnamed run).
std::string safe_file_name(std::string_view name) {
    std::string s = io::safe_file_name(name);
    return s.empty() ? std::string("explicit") : s;
}

Eigen::MatrixXd vec3_rows(const std::vector<Vec3>& v) {
    Eigen::MatrixXd m(v.size(), 3);
    for (std::size_t i = 0; i < v.size(); ++i) m.row(i) = v[i].transpose();
    return m;
}

std::string joined(const std::vector<std::string>& items) {
    std::string s;
    for (std::size_t i = 0; i < items.size(); ++i) s += (i ? "\n" : "") + items[i];
    return s;
}

std::vector<std::string> split_lines(const std::string& s) {
    std::vector<std::string> out;
    if (s.empty()) return out;
    std::size_t a = 0;
    while (true) {
        const std::size_t b = s.find('\n', a);
        out.push_back(s.substr(a, b == std::string::npos ? std::string::npos : b - a));
        if (b == std::string::npos) break;
        a = b + 1;
    }
    return out;
}

// One line per group: what must match between the dumping and the restarting model.
std::vector<std::string> group_signature(const ExplicitModel& model) {
    std::vector<std::string> g;
    for (const auto& grp : model.groups())
        g.push_back(fmt::format("part '{}' block {} {} with {} elements", grp->part, grp->block, grp->kind(), grp->size()));
    return g;
}

std::vector<std::string> provider_names(ExplicitModel& model) {
    std::vector<std::string> p;
    for (const auto& fp : model.force_providers()) p.push_back(fp->name());
    return p;
}
}  // namespace

std::vector<std::filesystem::path> ExplicitSolver::restart_files_in(const std::filesystem::path& dir, std::string_view name) {
    const std::string prefix = safe_file_name(name) + "-restart-";
    std::vector<std::pair<long, std::filesystem::path>> found;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
        const std::string f = e.path().filename().string();
        if (f.rfind(prefix, 0) != 0 || e.path().extension() != ".h5") continue;
        const std::string digits = f.substr(prefix.size(), f.size() - prefix.size() - 3);
        if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(c); })) continue;
        found.emplace_back(std::stol(digits), e.path());
    }
    std::sort(found.begin(), found.end());
    std::vector<std::filesystem::path> files;
    for (auto& [step, path] : found) files.push_back(std::move(path));
    return files;
}

std::filesystem::path ExplicitSolver::latest_restart(const std::filesystem::path& dir, std::string_view name) {
    const auto files = restart_files_in(dir, name);
    if (files.empty())
        throw InputError(fmt::format("no restart file of run '{}' ({}-restart-<step>.h5) in '{}'", name, safe_file_name(name),
                                     dir.string()));
    return files.back();
}

void ExplicitSolver::remove_older_restarts(const std::filesystem::path& dir, std::string_view name, std::size_t keep) {
    const auto files = restart_files_in(dir, name);
    for (std::size_t k = 0; k + keep < files.size(); ++k) std::filesystem::remove(files[k]);
}

void ExplicitSolver::restart_dumps() {
    const double tol = 1e-12 * opt_.end_time;
    bool due = false;
    std::size_t passed = 0;
    while (passed < restart_times_.size() && t_ + tol >= restart_times_[passed]) ++passed;
    if (passed > 0) {
        restart_times_.erase(restart_times_.begin(), restart_times_.begin() + static_cast<long>(passed));
        due = true;
    }
    if (opt_.restart_interval > 0.0 && t_ + tol >= next_restart_) {
        next_restart_ = t_ + opt_.restart_interval;
        due = true;
    }
    if (!due) return;
    const auto path = opt_.restart_dir / fmt::format("{}-restart-{:09d}.h5", safe_file_name(opt_.name), step_);
    write_restart(path);
    restart_files_.push_back(path);
}

double ExplicitSolver::restart_time(const std::filesystem::path& path) {
    const io::H5Reader r(path);
    if (r.attribute_string("/", "format") != kRestartFormat)
        throw InputError(fmt::format("restart file '{}' is not an explicit solver restart file ({})", path.string(), kRestartFormat));
    const std::vector<double> t = r.read("solver/t");
    if (t.size() != 1) throw InputError(fmt::format("restart file '{}': solver/t is not a number", path.string()));
    return t[0];
}

void ExplicitSolver::write_restart(const std::filesystem::path& path) const {
    io::H5Writer w(path);
    w.attribute("/", "format", kRestartFormat);
    w.attribute("/", "run", opt_.name);
    w.attribute("/", "time", t_);
    w.attribute("/", "step", static_cast<double>(step_));
    // What the restarting model must match.
    w.attribute("/", "nodes", static_cast<double>(s_.node_count()));
    w.attribute("/", "rotational_nodes", static_cast<double>(s_.rotational_count()));
    w.attribute("/", "groups", joined(group_signature(model_)));
    w.attribute("/", "force_providers", joined(provider_names(model_)));
    // Nodal state at t(n): x(n), v(n-1/2), the internal forces at x(n) (not recomputed on restart:
    // a group with history variables must not be evaluated twice), rotations.
    w.write("state/x", vec3_rows(s_.x));
    w.write("state/v", vec3_rows(s_.v));
    w.write("state/f", vec3_rows(s_.f));
    if (!s_.fv.empty()) w.write("state/fv", vec3_rows(s_.fv));
    w.write("state/omega", vec3_rows(s_.omega));
    w.write("state/moment", vec3_rows(s_.moment));
    Eigen::MatrixXd R(s_.rotational_count(), 9);
    for (int k = 0; k < s_.rotational_count(); ++k)
        for (int a = 0; a < 9; ++a) R(k, a) = s_.rotation[k](a / 3, a % 3);
    w.write("state/rotation", R);
    // Solver scalars: time and step control, energy accumulators, summary statistics, schedules.
    const EnergySummary& E = summary_.energy;
    const std::vector<std::pair<const char*, double>> scalars = {
        {"t", t_}, {"step", static_cast<double>(step_)}, {"dt_half", dt_half_}, {"dt_prev", dt_prev_},
        {"dt_crit", dt_crit_}, {"dt_crit_unscaled", dt_crit_unscaled_}, {"dt_group", static_cast<double>(dt_group_)},
        {"dt_element", static_cast<double>(dt_element_)}, {"stability_factor", stability_factor_},
        {"omega_max", omega_max_}, {"ctrl_min", ctrl_min_}, {"ctrl_group", static_cast<double>(ctrl_group_)},
        {"ctrl_element", static_cast<double>(ctrl_element_)}, {"e_int", e_int_}, {"e_hg", e_hg_},
        {"visc_power", visc_power_}, {"e_kin", e_kin_}, {"e_damp", e_damp_}, {"e_visc", e_visc_}, {"w_ext", w_ext_},
        {"w_abs", w_abs_}, {"w_prov", w_prov_}, {"e0", e0_}, {"input_scale", input_scale_},
        {"next_history", next_history_}, {"next_vtu", next_vtu_}, {"next_observer", next_observer_},
        {"last_observer", last_observer_}, {"first_dt", summary_.first_dt}, {"min_dt", summary_.min_dt},
        {"max_dt", summary_.max_dt}, {"controlling_dt", summary_.controlling_dt}, {"E_kinetic", E.kinetic},
        {"E_internal", E.internal}, {"E_hourglass", E.hourglass}, {"E_damping", E.damping}, {"E_viscous", E.viscous},
        {"E_external", E.external}, {"E_contact", E.contact}, {"E_initial", E.initial},
        {"E_balance_error", E.balance_error}, {"E_max_abs_balance_error", E.max_abs_balance_error},
        {"E_reference", E.reference}, {"E_max_internal", E.max_internal}, {"E_max_hourglass", E.max_hourglass},
        {"health_started", health_started_ ? 1.0 : 0.0}, {"balance_at_from", balance_at_from_}};
    for (const auto& [name, value] : scalars) w.write(std::string("solver/") + name, std::vector<double>{value});
    std::vector<double> part_max_int, part_max_hg;
    for (const auto& p : E.parts) part_max_int.push_back(p.max_internal), part_max_hg.push_back(p.max_hourglass);
    w.write("solver/part_max_internal", part_max_int);
    w.write("solver/part_max_hourglass", part_max_hg);
    w.write("solver/part_internal", part_int_);
    w.write("solver/part_hourglass", part_hg_);
    std::vector<std::string> vm_parts;
    std::vector<double> vm_values;
    for (const auto& [part, vm] : max_vm_) vm_parts.push_back(part), vm_values.push_back(vm);
    w.write("solver/max_vm", vm_values);
    w.attribute("/", "max_vm_parts", joined(vm_parts));
    w.write("solver/group_vm", group_vm_);
    // Histories so far (the restarted run's outputs then cover the whole run).
    const History& h = history_;
    w.write("history/time", h.time);
    std::vector<std::string> names;
    std::vector<long long> ids;
    for (std::size_t k = 0; k < h.nodes.size(); ++k) {
        names.push_back(h.nodes[k].name);
        ids.push_back(h.nodes[k].node);
        w.write(fmt::format("history/node{}/displacement", k), vec3_rows(h.nodes[k].displacement));
        w.write(fmt::format("history/node{}/velocity", k), vec3_rows(h.nodes[k].velocity));
    }
    w.write_ints("history/node_ids", ids);
    w.attribute("/", "history_node_names", joined(names));
    const std::vector<std::pair<const char*, const std::vector<double>*>> series = {
        {"kinetic", &h.kinetic}, {"internal", &h.internal}, {"hourglass", &h.hourglass}, {"damping", &h.damping},
        {"viscous", &h.viscous}, {"external", &h.external}, {"contact", &h.contact}, {"balance", &h.balance}};
    for (const auto& [name, v] : series) w.write(std::string("history/") + name, *v);
    std::vector<std::string> hv_parts;
    int k = 0;
    for (const auto& [part, v] : h.max_von_mises) {
        hv_parts.push_back(part);
        w.write(fmt::format("history/max_von_mises{}", k++), v);
    }
    w.attribute("/", "history_von_mises_parts", joined(hv_parts));
    // The VTU series so far.
    std::vector<double> pvd_t;
    std::vector<std::string> pvd_f;
    if (pvd_)
        for (const auto& [t, f] : pvd_->entries()) pvd_t.push_back(t), pvd_f.push_back(f);
    w.write("pvd/time", pvd_t);
    // absolute: a run resumed from another working folder still finds its series the same file
    w.attribute("/", "pvd_path", opt_.pvd_path.empty() ? std::string() : std::filesystem::absolute(opt_.pvd_path).string());
    w.attribute("/", "pvd_files", joined(pvd_f));
    // The groups' and force providers' own state.
    for (std::size_t g = 0; g < model_.groups().size(); ++g) model_.groups()[g]->save_state(w, fmt::format("groups/{}/", g));
    for (std::size_t p = 0; p < model_.force_providers().size(); ++p)
        model_.force_providers()[p]->save_state(w, fmt::format("providers/{}/", p));
    w.commit();
}

void ExplicitSolver::restore(const std::filesystem::path& path) {
    const io::H5Reader r(path);
    const std::string file = fmt::format("restart file '{}'", path.string());
    if (r.attribute_string("/", "format") != kRestartFormat)
        throw InputError(fmt::format("{} is not an explicit solver restart file ({})", file, kRestartFormat));
    // The model must be the one that wrote it (loads, motions, options may differ).
    const auto mismatch = [&](const std::string& what, const std::string& in_file, const std::string& in_model) {
        return InputError(fmt::format("{} does not match the model of run '{}': {} is {} in the file but {} in the "
                                      "model",
                                      file, opt_.name, what, in_file, in_model));
    };
    const auto n_file = static_cast<int>(r.attribute_number("/", "nodes"));
    if (n_file != s_.node_count())
        throw mismatch("the node count", std::to_string(n_file), std::to_string(s_.node_count()));
    const auto nr_file = static_cast<int>(r.attribute_number("/", "rotational_nodes"));
    if (nr_file != s_.rotational_count())
        throw mismatch("the number of nodes with rotations", std::to_string(nr_file), std::to_string(s_.rotational_count()));
    const auto groups_file = split_lines(r.attribute_string("/", "groups")), groups_model = group_signature(model_);
    for (std::size_t g = 0; g < std::max(groups_file.size(), groups_model.size()); ++g) {
        const std::string a = g < groups_file.size() ? groups_file[g] : "missing";
        const std::string b = g < groups_model.size() ? groups_model[g] : "missing";
        if (a != b) throw mismatch(fmt::format("element group {}", g), a, b);
    }
    const auto prov_file = split_lines(r.attribute_string("/", "force_providers")), prov_model = provider_names(model_);
    for (std::size_t p = 0; p < std::max(prov_file.size(), prov_model.size()); ++p) {
        const std::string a = p < prov_file.size() ? "'" + prov_file[p] + "'" : "missing";
        const std::string b = p < prov_model.size() ? "'" + prov_model[p] + "'" : "missing";
        if (a != b) throw mismatch(fmt::format("contact interface (force provider) {}", p), a, b);
    }
    // Nodal state.
    const auto read_vec3 = [&](const std::string& name, std::vector<Vec3>& v, int rows) {
        const Eigen::MatrixXd m = r.read_matrix(name);
        if (m.rows() != rows || (rows > 0 && m.cols() != 3))
            throw InputError(fmt::format("{}: dataset '{}' has {} rows, expected {}", file, name, m.rows(), rows));
        v.resize(rows);
        for (int i = 0; i < rows; ++i) v[i] = m.row(i).transpose();
    };
    const int n = s_.node_count(), nr = s_.rotational_count();
    read_vec3("state/x", s_.x, n);
    read_vec3("state/v", s_.v, n);
    read_vec3("state/f", s_.f, n);
    if (!s_.fv.empty()) {
        if (!r.has("state/fv"))
            throw InputError(fmt::format("{} has no viscous forces (state/fv), which this model books (a group with "
                                         "bulk viscosity or beta damping, exact_viscous_energy)",
                                         file));
        read_vec3("state/fv", s_.fv, n);
    }
    read_vec3("state/omega", s_.omega, nr);
    read_vec3("state/moment", s_.moment, nr);
    const Eigen::MatrixXd R = r.read_matrix("state/rotation");
    for (int k = 0; k < nr; ++k)
        for (int a = 0; a < 9; ++a) s_.rotation[k](a / 3, a % 3) = R(k, a);
    // Scalars.
    const auto get = [&](const char* name) {
        const std::vector<double> v = r.read(std::string("solver/") + name);
        if (v.size() != 1) throw InputError(fmt::format("{}: solver/{} is not a number", file, name));
        return v[0];
    };
    t_ = get("t");
    step_ = static_cast<long>(get("step"));
    dt_half_ = get("dt_half");
    dt_prev_ = get("dt_prev");
    dt_crit_ = get("dt_crit");
    dt_crit_unscaled_ = get("dt_crit_unscaled");
    dt_group_ = static_cast<int>(get("dt_group"));
    dt_element_ = static_cast<int>(get("dt_element"));
    stability_factor_ = get("stability_factor");
    omega_max_ = get("omega_max");
    ctrl_min_ = get("ctrl_min");
    ctrl_group_ = static_cast<int>(get("ctrl_group"));
    ctrl_element_ = static_cast<int>(get("ctrl_element"));
    e_int_ = get("e_int");
    e_hg_ = get("e_hg");
    visc_power_ = get("visc_power");
    e_kin_ = get("e_kin");
    e_damp_ = get("e_damp");
    e_visc_ = get("e_visc");
    w_ext_ = get("w_ext");
    w_abs_ = get("w_abs");
    w_prov_ = get("w_prov");
    e0_ = get("e0");
    input_scale_ = get("input_scale");
    next_history_ = get("next_history");
    next_vtu_ = get("next_vtu");
    next_observer_ = get("next_observer");
    last_observer_ = get("last_observer");
    summary_.first_dt = get("first_dt");
    summary_.min_dt = get("min_dt");
    summary_.max_dt = get("max_dt");
    summary_.controlling_dt = get("controlling_dt");
    EnergySummary& E = summary_.energy;
    E.kinetic = get("E_kinetic");
    E.internal = get("E_internal");
    E.hourglass = get("E_hourglass");
    E.damping = get("E_damping");
    E.viscous = get("E_viscous");
    E.external = get("E_external");
    E.contact = get("E_contact");
    E.initial = get("E_initial");
    E.balance_error = get("E_balance_error");
    E.max_abs_balance_error = get("E_max_abs_balance_error");
    E.reference = get("E_reference");
    if (r.has("solver/E_max_internal")) {  // (files written before the judged window have none)
        E.max_internal = get("E_max_internal");
        E.max_hourglass = get("E_max_hourglass");
        health_started_ = get("health_started") != 0.0;
        balance_at_from_ = get("balance_at_from");
    }
    if (r.has("solver/part_max_internal")) {  // per-part energies (files written before them have none)
        const auto max_int = r.read("solver/part_max_internal"), max_hg = r.read("solver/part_max_hourglass");
        const auto now_int = r.read("solver/part_internal"), now_hg = r.read("solver/part_hourglass");
        if (max_int.size() != E.parts.size() || max_hg.size() != E.parts.size() || now_int.size() != E.parts.size() ||
            now_hg.size() != E.parts.size())
            throw InputError(fmt::format("{}: {} parts with energies, the model has {}", file,
                                         max_int.size(), E.parts.size()));
        for (std::size_t p = 0; p < E.parts.size(); ++p) E.parts[p].max_internal = max_int[p], E.parts[p].max_hourglass = max_hg[p];
        part_int_ = now_int;
        part_hg_ = now_hg;
    }
    // The measured stability factor carries over (the start-up measurement is not repeated).
    auto& groups = model_.groups();
    apply_stability_factor(groups, stability_factor_, solid_, dt_factor_);
    summary_.stability_factor = stability_factor_;
    max_vm_.clear();
    const auto vm_parts = split_lines(r.attribute_string("/", "max_vm_parts"));
    const auto vm_values = r.read("solver/max_vm");
    for (std::size_t i = 0; i < vm_parts.size() && i < vm_values.size(); ++i) max_vm_[vm_parts[i]] = vm_values[i];
    group_vm_ = r.read("solver/group_vm");
    group_vm_.resize(groups.size());
    // Histories: continued when this run records the same nodes; otherwise a new history from here.
    std::vector<std::string> names;
    std::vector<long long> ids;
    for (const auto& h : history_.nodes) names.push_back(h.name), ids.push_back(h.node);
    if (split_lines(r.attribute_string("/", "history_node_names")) == names && r.read_ints("history/node_ids") == ids) {
        History& h = history_;
        h.time = r.read("history/time");
        const int samples = static_cast<int>(h.time.size());
        for (std::size_t k = 0; k < h.nodes.size(); ++k) {
            read_vec3(fmt::format("history/node{}/displacement", k), h.nodes[k].displacement, samples);
            read_vec3(fmt::format("history/node{}/velocity", k), h.nodes[k].velocity, samples);
        }
        const std::vector<std::pair<const char*, std::vector<double>*>> series = {
            {"kinetic", &h.kinetic}, {"internal", &h.internal}, {"hourglass", &h.hourglass}, {"damping", &h.damping},
            {"viscous", &h.viscous}, {"external", &h.external}, {"contact", &h.contact}, {"balance", &h.balance}};
        for (const auto& [name, v] : series) *v = r.read(std::string("history/") + name);
        int k = 0;
        for (const auto& part : split_lines(r.attribute_string("/", "history_von_mises_parts")))
            h.max_von_mises[part] = r.read(fmt::format("history/max_von_mises{}", k++));
    } else {
        next_history_ = t_;  // a new history, from the restart on
    }
    // The VTU series continues when it is the same file, or, for a branch of a shared start
    // (vtu_series_from_restart), from the dumping run's files, named relative to this PVD.
    if (pvd_) {
        const std::filesystem::path dumped = r.attribute_string("/", "pvd_path");
        const bool same = !dumped.empty() && std::filesystem::absolute(dumped) == std::filesystem::absolute(opt_.pvd_path);
        if (same || (!dumped.empty() && opt_.vtu_series_from_restart)) {
            const auto times = r.read("pvd/time");
            const auto files = split_lines(r.attribute_string("/", "pvd_files"));
            const std::filesystem::path from = dumped.parent_path(), here = std::filesystem::absolute(opt_.pvd_path).parent_path();
            std::vector<std::pair<double, std::string>> entries;
            for (std::size_t i = 0; i < times.size() && i < files.size(); ++i)
                entries.push_back({times[i], same ? files[i] : (from / files[i]).lexically_relative(here).generic_string()});
            pvd_->resume(std::move(entries));
        } else {
            next_vtu_ = t_;
        }
    }
    // The groups' and providers' own state (after the providers' initialize).
    for (std::size_t g = 0; g < groups.size(); ++g) groups[g]->restore_state(r, fmt::format("groups/{}/", g));
    for (std::size_t p = 0; p < model_.force_providers().size(); ++p)
        model_.force_providers()[p]->restore_state(r, fmt::format("providers/{}/", p));
    restarted_ = true;
}

double ExplicitSolver::choose_dt() const {
    // Force providers' springs (contact penalties) act in parallel with the elements, so
    // omega_max^2 <= omega_elements^2 + sum omega_p^2 (Weyl's inequality): the stable steps
    // combine as 1/dt^2 = 1/dt_e^2 + sum 1/dt_p^2. Taking only the smallest step is not enough:
    // two bars in penalty contact went unstable at 0.9 x min(dt_e, dt_p) (tests/contact).
    double inv2 = 1.0 / (dt_crit_ * dt_crit_);
    for (const auto& p : model_.force_providers()) {
        const double dp = p->stable_time_step(s_);
        if (std::isfinite(dp) && dp > 0.0) inv2 += 1.0 / (dp * dp);
    }
    double dt = opt_.dt_scale / std::sqrt(inv2);
    if (opt_.fixed_dt > 0.0) {
        dt = opt_.fixed_dt;
        if (dt > dt_crit_ && !opt_.allow_unstable_fixed_dt)
            throw SolverError(fmt::format(
                "explicit run '{}' at step {}, t = {:.6g} s: the fixed time step {:.4g} s is now above the critical "
                "step {:.4g} s of {} (the element deformed)",
                opt_.name, step_, t_, dt, dt_crit_, element_name(dt_group_, dt_element_)));
    }
    return dt;
}

RunSummary ExplicitSolver::run() {
    using Clock = std::chrono::steady_clock;
    const auto wall0 = Clock::now();
    // Progress on stderr (core/progress.hpp) and Ctrl-C as a clean stop after the current cycle.
    Progress progress(opt_.name, opt_.end_time, opt_.progress ? Progress::Mode::Auto : Progress::Mode::Quiet);
    const InterruptGuard interrupt_guard;
    gravity_c_ = std::numeric_limits<double>::quiet_NaN();  // fext_ recomputed at the first cycle (external_forces)
    const int n = s_.node_count(), nr = s_.rotational_count();
    const long cycles0 = element_cycles_, step0 = step_;

    // Timing (TimingSummary): lap(bucket) books the time since the last lap; a few clock reads per
    // cycle. The cost of one read, measured here, gives the timers' own cost in the summary.
    TimingSummary& T = timing_;
    T = TimingSummary{};
    {
        const auto c0 = Clock::now();
        for (int i = 0; i < 256; ++i) (void)Clock::now();
        T.timer_overhead = std::chrono::duration<double>(Clock::now() - c0).count() / 257.0;  // per read, for now
    }
    const double clock_read_s = T.timer_overhead;
    auto& providers_list = model_.force_providers();
    provider_s_.assign(providers_list.size(), 0.0);
    std::vector<double> search0;
    for (const auto& p : providers_list) search0.push_back(p->search_seconds());
    double skipped = 0.0;  // phases left to "other"
    auto mark = Clock::now();
    auto lap = [&](double& bucket) {
        const auto now = Clock::now();
        bucket += std::chrono::duration<double>(now - mark).count();
        mark = now;
        ++T.clock_reads;
    };

    EnergySummary& E = summary_.energy;
    if (!restarted_) {  // (a restarted run has all this from its file)
        dt_half_ = choose_dt();
        dt_prev_ = 0.0;
        summary_.first_dt = dt_half_;
        summary_.min_dt = std::numeric_limits<double>::infinity();
        summary_.max_dt = 0.0;
        // The controlling element: the one with the smallest critical step (stability factor
        // applied) over the run; the summary reports its step before the factor.
        ctrl_min_ = dt_crit_;
        summary_.controlling_dt = dt_crit_unscaled_;
        ctrl_group_ = dt_group_;
        ctrl_element_ = dt_element_;
        E.initial = e0_;
        E.kinetic = e_kin_;
        E.internal = e_int_;
        E.hourglass = e_hg_;
        record(true);
        write_vtu(0.0);
        notify_observer(true);
    } else if (history_.time.empty()) {
        record(true);  // a restart that records other nodes: a new history from the restart's state on
    }
    lap(T.output);

    // Energy bookkeeping: wext/damp are the work over step n of the forces at time n, taken with
    // the mid-point velocity (v(n-1/2) + v(n+1/2))/2; the *_half parts use v(n-1/2) alone. The
    // energy reported at time n adds only the half parts of step n, which makes the balance with
    // the kinetic energy 1/2 m v(n-1/2).v(n+1/2) and the strain energy at x(n) exact for a linear
    // system with loads (a constant force on a free mass balances to round-off).
    // The viscous forces of the groups that book them (s_.fv: bulk viscosity, stiffness damping) are
    // taken the same way: work f_visc(n) . (v(n-1/2) + v(n+1/2))/2 dt over step n, the half with
    // v(n-1/2) reported at n. That is exactly the energy the update removes, however strong and
    // abrupt the viscosity (booking the power at v(n-1/2) times dt is first order: off by
    // f_visc . (v(n+1/2) - v(n-1/2)) dt / 2 per step, tens of % in a violent impact, tests/explicit).
    using Partial = explicit_detail::NodeSums;
    const int chunks = par::chunk_count(n);
    std::vector<Partial> partial(chunks);
    const double tiny = 1e-12 * opt_.end_time;

    while (t_ < opt_.end_time - tiny && !stop_requested_ && !interrupt_requested()) {
        // No shortened last step: a change of step changes the discrete energy that central
        // differences conserve; the run ends at the first step at or after end_time (as LS-DYNA).
        const double dtavg = step_ == 0 ? 0.5 * dt_half_ : 0.5 * (dt_prev_ + dt_half_);
        external_forces(t_);
        const bool providers = !providers_list.empty();
        if (providers) {
            for (auto& f : fprov_) f.setZero();
            for (auto& m : mprov_) m.setZero();
            lap(skipped);
            for (std::size_t k = 0; k < providers_list.size(); ++k) {
                providers_list[k]->add_forces(t_, s_, fprov_, mprov_);
                lap(provider_s_[k]);
            }
        }
        // Prescribed motions: the velocity over the coming step that lands on the motion's position.
        for (const auto& mo : model_.motions()) {
            if (mo.position) {
                for (int node : mo.nodes) {
                    const Vec3 v = (mo.position(s_.X[node], t_ + dt_half_) - s_.x[node]) / dt_half_;
                    for (int d = 0; d < 3; ++d) target_[target_index_[node]][d] = v[d];
                }
                continue;
            }
            const RigidPose pose = mo.rigid.pose(t_ + dt_half_);  // once per motion and step
            for (int node : mo.nodes) {
                const Vec3 v = (pose.position(s_.X[node]) - s_.x[node]) / dt_half_;
                for (int d = 0; d < 3; ++d) target_[target_index_[node]][d] = v[d];
            }
        }
        // Prescribed velocities over the coming half step.
        for (const auto& p : model_.prescribed()) {
            const double tn = t_ + dt_half_;
            for (int node : p.nodes) {
                double v;
                if (p.displacement)
                    v = (p.value * p.curve(tn) - (s_.x[node][p.dof] - s_.X[node][p.dof])) / dt_half_;
                else
                    v = p.value * p.curve(t_ + 0.5 * dt_half_);
                target_[target_index_[node]][p.dof] = v;
            }
        }
        lap(T.constraints);
        // Central difference (Eq 2-5 with lumped M): v(n+1/2) from v(n-1/2), with the damping force
        // -alpha m v taken at the mid-point (v(n-1/2) + v(n+1/2))/2 (second order, unconditionally
        // stable for the damping term); x(n+1) = x(n) + dt v(n+1/2).
        // (explicit/node_update.cpp: the update of one chunk of nodes, compiled for AVX-512 too.)
        explicit_detail::NodeUpdateData nu;
        nu.mass = s_.mass.data();
        nu.alpha = alpha_.data();
        nu.fixed = fixed_.data();
        nu.target_index = target_index_.data();
        nu.target = target_.data();
        nu.f = s_.f.data();
        nu.fext = fext_.data();
        nu.fprov = providers ? fprov_.data() : nullptr;
        nu.fv = book_viscous_ ? s_.fv.data() : nullptr;
        nu.v = s_.v.data();
        nu.x = s_.x.data();
        nu.loads = has_loads_;
        nu.providers = providers;
        nu.book_viscous = book_viscous_;
        nu.dtavg = dtavg;
        nu.dt_half = dt_half_;
        par::for_each_index(chunks, n >= par::kParallelMin, [&](int c) {
            const auto [i0, i1] = par::chunk_range(c, n);
            partial[c] = explicit_detail::update_nodes(nu, i0, i1);
        });
        Partial tot;
        for (const auto& p : partial) {  // fixed order: deterministic
            tot.ke += p.ke;
            tot.ke_plus += p.ke_plus;
            tot.damp += p.damp;
            tot.wext += p.wext;
            tot.wabs += p.wabs;
            tot.wext_half += p.wext_half;
            tot.damp_half += p.damp_half;
            tot.wprov += p.wprov;
            tot.wprov_half += p.wprov_half;
            tot.visc += p.visc;
            tot.visc_half += p.visc_half;
            if (p.bad >= 0 && tot.bad < 0) tot.bad = p.bad;
        }
        // Rotational DOFs (beam nodes): isotropic inertia, so the gyroscopic term w x Jw vanishes;
        // the nodal triad is updated by the exponential map of w dt.
        for (int k = 0; k < nr; ++k) {
            const int node = s_.rot_node[k];
            const double J = s_.inertia[k];
            const Vec3 wm = s_.omega[k];
            const Vec3 M = providers ? Vec3(mext_[k] + mprov_[k] - s_.moment[k]) : Vec3(mext_[k] - s_.moment[k]);
            const double a = alpha_rot_[k] * dtavg * 0.5;
            Vec3 wp = ((1.0 - a) * wm + (dtavg / J) * M) / (1.0 + a);
            for (int d = 0; d < 3; ++d)
                if ((fixed_[node] >> (d + 3)) & 1u) {
                    wp[d] = 0.0;
                    const double wa = 0.5 * (wm[d] + wp[d]);
                    const double R = J * (wp[d] - wm[d]) / dtavg - M[d] + alpha_rot_[k] * J * wa;
                    tot.wext += R * dtavg * wa;
                    tot.wext_half += 0.5 * R * dtavg * wm[d];
                }
            const Vec3 wavg = 0.5 * (wm + wp);
            const double we = mext_[k].dot(wavg) * dtavg;
            tot.wext += we;
            tot.wext_half += 0.5 * mext_[k].dot(wm) * dtavg;
            tot.wabs += std::abs(we);
            tot.damp += alpha_rot_[k] * J * wavg.squaredNorm() * dtavg;
            tot.damp_half += 0.5 * alpha_rot_[k] * J * wavg.dot(wm) * dtavg;
            if (providers) {
                tot.wprov += mprov_[k].dot(wavg) * dtavg;
                tot.wprov_half += 0.5 * mprov_[k].dot(wm) * dtavg;
            }
            tot.ke += 0.5 * J * wm.dot(wp);
            tot.ke_plus += 0.5 * J * wp.squaredNorm();
            if (!std::isfinite(wp.squaredNorm()) && tot.bad < 0) tot.bad = node;
            s_.omega[k] = wp;
            beam::rotate(dt_half_ * wp, s_.rotation[k]);  // exp([w dt]x) R (Rodrigues)
        }
        // Energy balance at time n (kinetic from v(n-1/2).v(n+1/2), strain energy at x(n)).
        E.kinetic = tot.ke;
        E.internal = e_int_;
        E.hourglass = e_hg_;
        E.damping = e_damp_ + tot.damp_half;
        E.viscous = e_visc_ + 0.5 * visc_power_ * dtavg + tot.visc_half;
        E.external = w_ext_ + tot.wext_half;
        E.contact = -(w_prov_ + tot.wprov_half);
        w_prov_ += tot.wprov;
        w_ext_ += tot.wext;
        w_abs_ += tot.wabs;
        e_damp_ += tot.damp;
        e_visc_ += visc_power_ * dtavg + tot.visc;
        E.balance_error =
            E.kinetic + E.internal + E.hourglass + E.damping + E.viscous + E.contact - E.external - E.initial;
        // Energy health over the judged window (EnergySummary; the balance at time n is t_'s).
        if (t_ >= opt_.health_from - tiny && t_ <= opt_.health_until + tiny) {
            if (!health_started_) {
                health_started_ = true;
                balance_at_from_ = opt_.health_from > 0.0 ? E.balance_error : 0.0;  // the error made before it
            }
            E.max_abs_balance_error = std::max(E.max_abs_balance_error, std::abs(E.balance_error - balance_at_from_));
            E.max_internal = std::max(E.max_internal, E.internal);
            E.max_hourglass = std::max(E.max_hourglass, std::abs(E.hourglass));
            E.reference = std::max(E.reference, E.total());
        }
        for (std::size_t p = 0; p < E.parts.size(); ++p) {
            E.parts[p].max_internal = std::max(E.parts[p].max_internal, part_int_[p]);
            E.parts[p].max_hourglass = std::max(E.parts[p].max_hourglass, std::abs(part_hg_[p]));
        }
        input_scale_ = std::abs(e0_) + w_abs_ + std::abs(w_prov_);  // the energy put in (growth detector)

        if (tot.bad >= 0) unstable("a velocity became non-finite");
        if (tot.ke_plus + e_int_ + e_hg_ > opt_.energy_growth_factor * input_scale_ && input_scale_ > 0.0)
            unstable(fmt::format("the kinetic + internal energy {:.4g} J exceeds {} x the energy put in ({:.4g} J)",
                                 tot.ke_plus + e_int_ + e_hg_, opt_.energy_growth_factor, input_scale_));

        summary_.min_dt = std::min(summary_.min_dt, dt_half_);
        summary_.max_dt = std::max(summary_.max_dt, dt_half_);
        t_ += dt_half_;
        ++step_;
        lap(T.update);
        // Forces at x(n+1) (rate terms from v(n+1/2)); critical step every dt_interval cycles.
        compute_forces(step_ % opt_.dt_interval == 0);
        lap(T.elements);
        if (dt_crit_ < ctrl_min_) {
            ctrl_min_ = dt_crit_;
            summary_.controlling_dt = dt_crit_unscaled_;
            ctrl_group_ = dt_group_;
            ctrl_element_ = dt_element_;
        }
        dt_prev_ = dt_half_;
        dt_half_ = choose_dt();
        lap(skipped);
        record(false);
        write_vtu(t_);
        notify_observer(false);
        restart_dumps();
        lap(T.output);
        if (progress.due(t_)) {
            const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
            progress.show(t_, fmt::format("t = {:.4g} of {:.4g} s, step {}, {:.3g} element-cycles/s", t_, opt_.end_time, step_,
                                          wall > 0 ? static_cast<double>(element_cycles_ - cycles0) / wall : 0.0));
        }
    }
    progress.finish();
    // Ctrl-C: the outputs below are written for the state reached, marked partial, then Interrupted.
    const bool interrupted = interrupt_requested() && t_ < opt_.end_time - tiny;
    const std::string partial_note =
        interrupted ? fmt::format("partial: interrupted (Ctrl-C) at t = {:.6g} s of {:.6g} s, step {}", t_, opt_.end_time, step_)
                    : "";
    if (pvd_ && next_vtu_ > t_) {  // the last state, unless just written
        next_vtu_ = t_;
        write_vtu(t_);
    }
    // The last state (kinetic energy at t_end from v(n-1/2) alone: no v(n+1/2) exists yet).
    if (history_.time.empty() || history_.time.back() < t_) record(true);
    if (last_observer_ < t_) notify_observer(true);

    summary_.steps = step_;
    summary_.end_time = t_;
    summary_.threads = par::threads();
    if (ctrl_group_ >= 0) {
        const auto& g = *model_.groups()[ctrl_group_];
        summary_.controlling_part = g.part;
        summary_.controlling_kind = g.kind();
        summary_.controlling_block = g.block;
        // Its number as the user knows it (ElementBlock::id), as the messages name elements.
        summary_.controlling_element =
            static_cast<int>(g.block >= 0 ? model_.mesh().blocks[g.block].id(ctrl_element_) : ctrl_element_ + 1L);
        summary_.controlling_rule = g.time_step_rule(ctrl_element_);
    }
    // What limits the step now (choose_dt's terms).
    summary_.step_limits = {{"elements", dt_crit_}};
    for (const auto& p : model_.force_providers()) {
        const double dp = p->stable_time_step(s_);
        if (std::isfinite(dp) && dp > 0.0) summary_.step_limits.push_back({fmt::format("'{}'", p->name()), dp});
    }
    summary_.step_at_end = choose_dt();
    // Timing table and contact interfaces (the final HDF5 below counts as output, measured first).
    summary_.interfaces.clear();
    for (std::size_t k = 0; k < providers_list.size(); ++k) {
        const double search = providers_list[k]->search_seconds() - search0[k];
        T.contact_search += search;
        T.contact_forces += provider_s_[k] - search;
        const ContactReport c = providers_list[k]->contact_report();
        if (!c.is_contact) continue;
        summary_.interfaces.push_back({providers_list[k]->name(), c.max_penetration, c.max_penetration_fraction,
                                       c.stored_energy + c.dissipated_energy, c.stored_energy, c.dissipated_energy,
                                       search, provider_s_[k] - search});
    }
    // The contact interfaces read the clock twice per pass and cycle (their search time).
    T.clock_reads += 2 * static_cast<long>(providers_list.size()) * (step_ - step0);
    const auto finish_timing = [&]() {
        lap(T.output);
        const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
        T.timer_overhead = clock_read_s * static_cast<double>(T.clock_reads);
        T.other = std::max(0.0, wall - (T.elements + T.contact_search + T.contact_forces + T.constraints + T.update +
                                        T.output));
        summary_.timing = T;
        summary_.wall_s = wall;
        summary_.element_cycles_per_s = wall > 0 ? static_cast<double>(element_cycles_ - cycles0) / wall : 0.0;
    };
    finish_timing();
    if (!opt_.h5_path.empty()) {
        io::H5Writer w(opt_.h5_path);
        w.write("time", history_.time);
        for (const auto& h : history_.nodes) {
            Eigen::MatrixXd u(h.displacement.size(), 3), v(h.velocity.size(), 3);
            for (std::size_t i = 0; i < h.displacement.size(); ++i) {
                u.row(i) = h.displacement[i].transpose();
                v.row(i) = h.velocity[i].transpose();
            }
            w.write("history/" + h.name + "/displacement", u);
            w.write("history/" + h.name + "/velocity", v);
            w.attribute("history/" + h.name + "/displacement", "node", static_cast<double>(h.node));
        }
        w.write("energy/kinetic", history_.kinetic);
        w.write("energy/internal", history_.internal);
        w.write("energy/hourglass", history_.hourglass);
        w.write("energy/damping", history_.damping);
        w.write("energy/viscous", history_.viscous);
        w.write("energy/external_work", history_.external);
        w.write("energy/contact", history_.contact);
        w.write("energy/balance_error", history_.balance);
        for (const auto& [part, vm] : history_.max_von_mises) w.write("max_von_mises/" + part, vm);
        // The summary without its timings (wall time, speed, threads: runs.json has them), so that
        // identical runs give byte-identical files whatever the machine's load or thread count.
        nlohmann::json summary = summary_.to_json();
        RunSummary::erase_machine_facts(summary);
        w.attribute("/", "summary", summary.dump());
        if (interrupted) w.attribute("/", "partial", partial_note);
        w.commit();
    }
    finish_timing();  // with the HDF5 file
    if (opt_.print_summary) std::cout << summary_.text() << (interrupted ? partial_note + "\n" : "") << std::flush;
    if (interrupted) {  // the flag stays set: other runs going on at once stop as well
        throw Interrupted(fmt::format("explicit run '{}': {}{}{}", opt_.name, partial_note,
                                      opt_.h5_path.empty() ? "" : "; histories in " + opt_.h5_path.string(),
                                      opt_.pvd_path.empty() ? "" : "; states in " + opt_.pvd_path.string()));
    }
    return summary_;
}

}  // namespace fem
