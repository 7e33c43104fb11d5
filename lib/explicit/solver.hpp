#pragma once
// Explicit dynamic solver (thesis Sec 2.3 and 2.5): central-difference integration of
// M a + C v + f_int(x) = f_ext (Eq 2-5) with a lumped diagonal mass, a time step of 0.9 x the
// smallest element critical step of Table 2-1 re-evaluated on the current coordinates (Eq 2-27),
// mass-proportional Rayleigh damping per part (Eq 2-39, like *DAMPING_PART_MASS), bulk viscosity
// and stiffness damping in solids, loads, constraints, energy accounting, histories and output.
//
// Usage: the compliant beam of thesis Table 2-8 (0.4 m steel wire, d = 0.6 mm, 100 beam elements,
// 0.015 g tip mass, 0.003 N tip load for 0.2 s, then free vibration):
//
//   #include "explicit/solver.hpp"
//   using namespace fem;
//   Mesh mesh = line_beam2(Vec3(0, 0, 0), Vec3(0.4, 0, 0), 100, "beam");    // nodes sets start/end
//   const auto steel = ElasticMaterial::make("steel", 209e9, 0.3, 7957);
//   ExplicitModel model(mesh);
//   model.add_beams("beam", steel, {beam::Section::circular(0.6e-3)});
//   const int tip = mesh.node_set("end")[0];
//   model.add_point_mass("tip mass", tip, 0.015e-3);
//   model.fix(mesh.node_set("start"), Dofs::all());                         // clamped root
//   model.add_nodal_force({tip}, Vec3(0, -0.003, 0), Curve::pulse(0.0, 0.2)); // 0.003 N for 0.2 s
//   model.set_mass_damping("beam", 0.165);  model.set_mass_damping("tip mass", 0.165);  // alpha, Table 2-10
//   ExplicitOptions opt;  opt.end_time = 4.0;  opt.history_nodes = {{"tip", tip}};
//   opt.history_interval = 1e-3;  opt.h5_path = "tip.h5";                       // optional outputs
//   ExplicitSolver solver(model, opt);
//   RunSummary summary = solver.run();        // prints the d3hsp/glstat-like summary
//   const History& h = solver.history();      // h.time, h.nodes[0].displacement[i].y(), energies
//   study.record_run({"compliant_beam", summary.to_json()});
//
// Sign convention: internal forces are resisting forces; a = (f_ext - f_int - alpha m v) / m.
// Kinetic energy is reported as 1/2 m v(n-1/2).v(n+1/2), the quantity that the central-difference
// scheme conserves exactly together with the strain energy of a linear system. External work, mass
// damping and the viscous forces of groups that report them per node (ElementGroup::
// adds_viscous_forces) are booked as force at n times (v(n-1/2) + v(n+1/2))/2 times dt, exactly what
// the update does, so the energy balance error measures the nonlinear elastic terms only (and the
// first-order booking of viscous power for groups that report only its total).
#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "explicit/curve.hpp"
#include "explicit/element_group.hpp"
#include "explicit/groups.hpp"
#include "explicit/rigid_motion.hpp"
#include "explicit/shell_group.hpp"
#include "io/vtu.hpp"
#include "mesh/mesh.hpp"

namespace fem {

/// Degrees of freedom, as a bit mask: Dofs::x | Dofs::y ... (global axes).
struct Dofs {
    unsigned mask = 0;
    static constexpr unsigned x = 1, y = 2, z = 4, rx = 8, ry = 16, rz = 32;
    static Dofs all() { return {63}; }
    static Dofs translations() { return {7}; }
    static Dofs rotations() { return {56}; }
    static Dofs of(unsigned m) { return {m}; }
    bool has(int dof) const { return (mask >> dof) & 1u; }  // dof 0..5
};

/// The model: mesh, element groups (parts), constraints, loads, damping, initial conditions.
class ExplicitModel {
public:
    explicit ExplicitModel(Mesh mesh);
    const Mesh& mesh() const { return mesh_; }

    // --- parts (one group per block of the part) ---
    void add_hex8(std::string_view part, const ElasticMaterial& material, const Hex8Options& options = {});
    void add_beams(std::string_view part, const ElasticMaterial& material, const BeamOptions& options);
    /// Belytschko-Tsay shells (quad4; tri3 as degenerate quads) of thickness options.thickness on
    /// every block of `part` (explicit/shell_group.hpp).
    void add_shells(std::string_view part, const ElasticMaterial& material, const ShellOptions& options);
    /// A point mass on one node (thesis "Mass 166"); several calls with the same part name add to it.
    void add_point_mass(const std::string& part, int node, double mass, double rotational_inertia = 0.0);
    /// Every Point1 element of a Point1 block `part` gets `mass_each`.
    void add_point_masses(std::string_view part, double mass_each, double rotational_inertia_each = 0.0);
    /// Any other element group (shells, tetrahedra later).
    void add_group(std::unique_ptr<ElementGroup> group);

    // --- constraints and loads ---
    void fix(const std::vector<int>& nodes, Dofs dofs = Dofs::all());
    /// Symmetry plane of a half (or quarter) model: the nodes within `tolerance` of the plane through
    /// `point` with normal `normal` get the normal translation fixed and, when they carry rotations
    /// (beams, shells), the two rotations about the in-plane axes (the rotation about the normal
    /// stays free). Returns those nodes; InputError when there are none. tolerance <= 0: 1e-9 x the
    /// mesh's bounding-box diagonal. Only planes whose normal is a global axis (+-x, +-y, +-z) can be
    /// expressed: the constraint is a fixed global DOF, and a skew plane would need a local frame per
    /// node, which the solver does not have; any other normal is refused with an InputError.
    std::vector<int> add_symmetry_plane(const Vec3& normal, const Vec3& point, double tolerance = 0.0);
    /// The same on the given nodes (e.g. a node set), without looking at their coordinates.
    void add_symmetry_plane(const Vec3& normal, const std::vector<int>& nodes);
    /// Prescribed velocity v(t) = value * curve(t) along global dof (0..2 translations, 3..5 rotations).
    void prescribe_velocity(const std::vector<int>& nodes, int dof, double value, Curve curve = {});
    /// Nodes that follow a rigid motion exactly (all three translations; rigid_motion.hpp), e.g. the
    /// finger root nodes tied to the turning drum. A node may follow one motion only, and not be
    /// fixed as well (InputError).
    void prescribe_motion(const std::vector<int>& nodes, RigidMotion motion);
    /// Nodes that follow x(t) = position(X, t) exactly (any motion; position(X, 0) should be X).
    void prescribe_motion(const std::vector<int>& nodes, std::function<Vec3(const Vec3& X, double t)> position);
    /// A rigid part (LS-DYNA *MAT_RIGID with a prescribed motion): every node of the blocks of `part`
    /// (solids, shells, any shape) follows `motion` exactly. The part gets no element group: no
    /// element work, no mass (a prescribed body's inertia does not act on the rest). Its faces can be
    /// a contact master (contact::ContactSurface::rigid_part; the interface reports the reaction on
    /// it), and it is written to the VTU output with the rest (von Mises 0). Nodes it shares with a
    /// deformable part are tied to it, and the work of their reactions is external work. Throws
    /// InputError when the part does not exist, is already rigid, or (when the solver starts) also
    /// has element groups.
    void add_rigid_part(std::string_view part, RigidMotion motion);
    /// Contact and other state-dependent forces (see ForceProvider); returns a reference to it.
    ForceProvider& add_force_provider(std::unique_ptr<ForceProvider> provider);
    /// Prescribed displacement u(t) = value * curve(t) along dof (measured from the reference position;
    /// translations only).
    void prescribe_displacement(const std::vector<int>& nodes, int dof, double value, Curve curve);
    /// A force (per node, global) scaled by curve(t).
    void add_nodal_force(const std::vector<int>& nodes, const Vec3& force, Curve curve = {});
    /// A moment (per node, global) scaled by curve(t); the nodes must carry rotations (beams).
    void add_nodal_moment(const std::vector<int>& nodes, const Vec3& moment, Curve curve = {});
    /// Gravity acceleration g switched on at t_on (body force m g on every node's mass).
    void set_gravity(const Vec3& g, double t_on = 0.0);
    /// Gravity g x curve(t), e.g. Curve::step(t_on) or a ramp (body force m g curve(t)).
    void set_gravity(const Vec3& g, Curve curve);
    /// Mass-proportional damping alpha [1/s] of Eq 2-39 on the nodes of `part` (force -alpha m v,
    /// also on rotations), like *DAMPING_PART_MASS. A node shared by parts takes the largest alpha.
    void set_mass_damping(std::string_view part, double alpha);
    /// Mass-proportional damping on every node.
    void set_mass_damping(double alpha);

    // --- initial conditions ---
    void set_initial_velocity(const std::vector<int>& nodes, const Vec3& v);
    /// Initial velocity from a function of the reference position (e.g. a rigid spin or a mode).
    void set_initial_velocity(const std::function<Vec3(const Vec3&)>& v_of_x);
    void set_initial_angular_velocity(const std::vector<int>& nodes, const Vec3& w);

    // --- internals used by the solver ---
    struct Prescribed {
        std::vector<int> nodes;
        int dof;
        double value;
        Curve curve;
        bool displacement;
    };
    struct NodalLoad {
        std::vector<int> nodes;
        Vec3 value;
        Curve curve;
        bool moment;
    };
    /// A prescribed motion of nodes: the rigid motion, or (when set) the general `position`.
    struct Motion {
        std::vector<int> nodes;
        RigidMotion rigid;
        std::function<Vec3(const Vec3&, double)> position;
        std::string part;  // the rigid part's name (empty: nodes tied by prescribe_motion)
    };
    const std::vector<Motion>& motions() const { return motions_; }
    std::vector<std::unique_ptr<ForceProvider>>& force_providers() { return providers_; }
    std::vector<std::unique_ptr<ElementGroup>>& groups() { return groups_; }
    const std::vector<std::unique_ptr<ElementGroup>>& groups() const { return groups_; }
    const std::vector<unsigned>& fixed() const { return fixed_; }
    const std::vector<Prescribed>& prescribed() const { return prescribed_; }
    const std::vector<NodalLoad>& loads() const { return loads_; }
    const std::map<std::string, double, std::less<>>& mass_damping() const { return damping_; }
    double global_mass_damping() const { return global_alpha_; }
    const Vec3& gravity() const { return gravity_; }
    const Curve& gravity_curve() const { return gravity_curve_; }
    const std::vector<Vec3>& initial_velocity() const { return v0_; }
    const std::map<int, Vec3>& initial_angular_velocity() const { return w0_; }

private:
    void check_nodes(const std::vector<int>& nodes, const char* what) const;
    Mesh mesh_;
    std::vector<std::unique_ptr<ElementGroup>> groups_;
    std::map<std::string, std::pair<std::vector<int>, std::pair<std::vector<double>, std::vector<double>>>,
             std::less<>>
        point_data_;
    std::vector<unsigned> fixed_;
    std::vector<Prescribed> prescribed_;
    std::vector<NodalLoad> loads_;
    std::vector<Motion> motions_;
    std::vector<std::unique_ptr<ForceProvider>> providers_;
    std::map<std::string, double, std::less<>> damping_;
    double global_alpha_ = 0.0;
    Vec3 gravity_ = Vec3::Zero();
    Curve gravity_curve_;
    std::vector<Vec3> v0_;
    std::map<int, Vec3> w0_;
    bool finalized_ = false;
    void finalize();  // turns the collected point masses into groups (called by the solver)
    friend class ExplicitSolver;
};

struct HistoryNode {
    std::string name;
    int node = -1;
};

struct ExplicitOptions {
    double end_time = 0.0;           // [s]
    double dt_scale = 0.9;           // a of Eq 2-27
    double fixed_dt = 0.0;           // > 0: use this step; refused (InputError) when above critical
    bool allow_unstable_fixed_dt = false;  // testing the instability detector only
    int dt_interval = 1;             // re-evaluate the critical step every N cycles (1: every cycle)
    double mass_scaling_dt = 0.0;    // > 0: selective mass scaling so that the step is at least this
    double energy_growth_factor = 10.0;  // instability when KE + IE exceeds this x the energy put in
    // Table 2-1's solid steps are not stability bounds: one-point hexahedra whose nodes are shared
    // by few elements (surfaces, edges, corners) have a higher omega_max than V/A_max predicts (a
    // free cube: 0.73 x the Table 2-1 step at nu = 0.3, 0.58 at nu = 0.49; a 6x6x6 rubber block
    // 0.86), tet10 with HRZ masses up to 2.8x (tet_groups.hpp), so 0.9 x Table 2-1 can be unstable.
    // When true, the solver measures omega_max of all solid groups (hexahedra, tetrahedra: every
    // group without rotational DOFs that has a critical step) together once at the start (Lanczos,
    // Spectra, on the lumped-mass system with the constraints) and scales their Table 2-1 steps by
    // min(1, (2/omega_max) / smallest Table 2-1 step of those groups). (The name is historical: it
    // covers every solid group.)
    bool hex_stability_check = true;
    // Book the work of bulk viscosity and beta damping exactly (the groups' viscous nodal forces at n
    // times the mid-interval velocity, as mass damping): needed for a trustworthy energy balance
    // under strong viscosity (a violent hex8 impact: balance error 3.6e-2 first-order, 4.9e-4
    // exact). Costs ~15 % of a whole hex8 solver step (a second nodal scatter); false books the
    // viscous power at v(n-1/2) times dt instead.
    bool exact_viscous_energy = true;
    // Histories (in memory, and in HDF5 when h5_path is set).
    std::vector<HistoryNode> history_nodes;
    double history_interval = 0.0;   // [s]; 0: every cycle
    std::filesystem::path h5_path;
    // Deformed states for ParaView (VTU files listed in a PVD) every vtu_interval.
    std::filesystem::path pvd_path;
    double vtu_interval = 0.0;
    // Restart dumps (LS-DYNA's d3dump): the complete solver state, written at the first cycle at or
    // after each of restart_times and/or every restart_interval [s], one HDF5 file per dump,
    // <restart_dir>/<name>-restart-<step>.h5 (step zero-padded, so the names sort in time), each
    // written under a temporary name and renamed (a killed run never leaves a half-written dump).
    // restart_from: start from such a file instead of t = 0, with this model and these options (which
    // may change loads, motions, gravity, damping, end time, outputs: a "full deck restart"); the
    // model must have the same mesh, groups and force providers (else InputError). With an unchanged
    // model and options the run continues bit for bit as if it had never stopped (README: restart).
    std::vector<double> restart_times;
    double restart_interval = 0.0;
    std::filesystem::path restart_dir;
    std::filesystem::path restart_from;
    // A branch of a shared start: restart_from is another run's dump (cases that run alike until a
    // switch, e.g. a drum speed that changes at 0.55 s in some of them, share the run up to it), and
    // this run's PVD lists that run's VTU files written before the dump (paths relative to this
    // PVD's folder), then its own, numbered on from them: the series covers the whole run, as an
    // uninterrupted run's would. false: a restart from another PVD's dump starts a series there.
    bool vtu_series_from_restart = false;
    // When the observer runs: < 0 at every history sample (the default); 0 every cycle; > 0 every
    // observer_interval [s] (the first cycle at or after each), whatever the history interval. So an
    // observer can watch every cycle without the history storing every cycle.
    double observer_interval = -1.0;
    // The window of model time [health_from, health_until] the run's energy health is judged over
    // (EnergySummary's balance error, energy scale and hourglass share; check/run_health judges
    // them): the whole run by default. A study whose checks read a window of a longer run gives it,
    // so that its judged numbers do not depend on how far the run goes (ellipsoid_flip: the grasp
    // to 1.55 s of a --full run to 2 s). The balance error is the error made within the window.
    double health_from = 0.0;
    double health_until = std::numeric_limits<double>::infinity();
    std::string name = "explicit";   // run name in the summary
    bool print_summary = true;       // to stdout at the end
    bool progress = true;            // an updating line on stderr, only when it is a terminal
};

/// Time histories recorded every history_interval: at time[i] the displacement is x(n+1) - X at
/// t(n+1) = time[i], the velocity is v(n+1/2) (half a step earlier), and the energies are those of
/// the balance at t(n), one step earlier (they need v(n+1/2)); negligible at output intervals.
struct History {
    struct Node {
        std::string name;
        int node = -1;
        std::vector<Vec3> displacement, velocity;
    };
    std::vector<double> time;
    std::vector<Node> nodes;
    std::vector<double> kinetic, internal, hourglass, damping, viscous, external, contact, balance;
    std::map<std::string, std::vector<double>> max_von_mises;  // per part
};

/// Largest internal and hourglass energies of one part over the run (the same measure as
/// EnergySummary::hourglass_fraction, per part): which part carries the hourglass energy.
struct PartEnergy {
    std::string part;
    double max_internal = 0, max_hourglass = 0;  // [J]
    double hourglass_fraction() const {
        return max_internal > 0 ? max_hourglass / max_internal : (max_hourglass > 0 ? 1.0 : 0.0);
    }
};

/// The energies of a run at its end, and its energy health (LS-DYNA glstat conventions) over the
/// judged window (ExplicitOptions::health_from/health_until, the whole run by default):
///   relative_error() = max |balance error - its value at the window start| / reference, where
///   reference is the largest total energy in the window: kinetic + internal + hourglass + damping +
///   viscous + contact (when positive), i.e. the initial energy plus the work done on the system
///   (loads, prescribed motions, moving contact masters) when the balance holds: glstat's "energy
///   ratio" denominator (initial energy + external work);
///   hourglass_fraction() = largest hourglass energy / largest internal energy in the window.
struct EnergySummary {
    double kinetic = 0, internal = 0, hourglass = 0;
    double damping = 0;       // dissipated by mass-proportional damping
    double viscous = 0;       // dissipated by bulk viscosity and stiffness damping
    double external = 0;      // work of loads, gravity and prescribed motion (reactions)
    double contact = 0;       // energy taken by force providers (contact): minus their work
    double initial = 0;       // total energy at t = 0
    double balance_error = 0; // kinetic + internal + hourglass + damping + viscous + contact - external - initial
    double max_abs_balance_error = 0;  // over the window, from its start
    double reference = 0;     // energy scale the relative error is taken against: largest total() in the window
    double max_internal = 0, max_hourglass = 0;  // largest in the window (the health measure below)
    double window_from = 0, window_until = std::numeric_limits<double>::infinity();  // the judged window [s]
    /// The total energy incl. what was dissipated: the initial energy plus the work done on the
    /// system when the balance holds (a negative contact energy is work done by moving contact
    /// masters, already in the other terms).
    double total() const { return kinetic + internal + hourglass + damping + viscous + std::max(contact, 0.0); }
    double relative_error() const { return reference > 0 ? max_abs_balance_error / reference : 0.0; }
    /// Hourglass energy as a fraction of internal energy: their largest values in the window, so that
    /// a run whose internal energy has decayed at the end is still judged where it mattered (the
    /// LS-DYNA rule of thumb: below 10 %; check/run_health.hpp).
    double hourglass_fraction() const { return max_internal > 0 ? max_hourglass / max_internal : (max_hourglass > 0 ? 1.0 : 0.0); }
    std::vector<PartEnergy> parts;  // per part of the model's element groups, in the order they were added
};

/// Where the wall time of a run went (LS-DYNA's timing table at the end of d3hsp) [s]. Measured
/// per cycle around each phase (a few clock reads per cycle, never per element or node):
/// elements = internal forces of every group (with the element time steps); contact_search and
/// contact_forces = the force providers (their own search time, ForceProvider::search_seconds, and
/// the rest of add_forces); constraints = prescribed motions, rigid parts and prescribed velocities
/// (their target velocities); update = the central-difference update of velocities and positions
/// with the energy sums; output = histories, observer, VTU, restart dumps and the final HDF5;
/// other = the rest of the wall time (loads and gravity, the step choice, progress line).
struct TimingSummary {
    double elements = 0, contact_search = 0, contact_forces = 0, constraints = 0, update = 0, output = 0, other = 0;
    double timer_overhead = 0;  // estimated cost of the clock reads themselves (count x measured cost of one)
    long clock_reads = 0;
};

/// Per contact interface (ForceProvider::contact_report), over the run.
struct InterfaceSummary {
    std::string name;
    double max_penetration = 0;           // [m]
    double max_penetration_fraction = 0;  // of the slave's local element size
    double energy = 0, stored_energy = 0, dissipated_energy = 0;  // contact energy = stored + dissipated [J]
    double search_s = 0, forces_s = 0;    // wall time
};

/// The run summary (LS-DYNA d3hsp/glstat style); to_json() feeds Study::record_run.
struct RunSummary {
    std::string name;
    int nodes = 0, elements = 0, rotational_nodes = 0, threads = 1;
    long steps = 0;
    double end_time = 0, first_dt = 0, min_dt = 0, max_dt = 0;
    std::vector<std::string> rigid_parts;
    std::string controlling_part, controlling_kind;
    std::string controlling_rule;  // which rule gives its step (ElementGroup::time_step_rule)
    int controlling_block = -1, controlling_element = -1;
    double controlling_dt = 0;   // its critical step (before the 0.9 and the stability factor)
    double stability_factor = 1; // measured 2/omega_max over the smallest solid Table 2-1 step (solid groups; may exceed 1 for tetrahedra)
    /// Of the hexahedra with bulk viscosity flatter than cbrt(V) = 2 V / A_max (README "Flat hexahedra
    /// and bulk viscosity"), the one nearest its damped step limit: which element (empty: none), its
    /// ratio cbrt(V) / (V / A_max), and its damped limit over the run's step bound in compression
    /// (cfl::flat_hexahedron_step_factor; below 1 the run is likely to go unstable). run.json has null
    /// for the ratio and margin when none is named.
    std::string flat_hex;
    double flat_hex_ratio = 0;
    double flat_hex_margin = 0;
    std::string flat_hex_warning;  // when its margin is below 1.03 (the model's accuracy): what to do
    double mass = 0, added_mass = 0, added_mass_fraction = 0;
    // What limits the step at the end (ExplicitSolver::choose_dt): the elements' stable step and each
    // force provider's (contact penalties, ties), combined as 1/dt^2 = sum 1/dt_i^2 before the
    // dt_scale; providers without a limit are left out. Tells a user whether a contact's springs or
    // an element hold the step down (LS-DYNA's d3hsp lists the smallest element steps only).
    struct StepLimit {
        std::string name;
        double dt = 0;
    };
    std::vector<StepLimit> step_limits;
    double step_at_end = 0;  // the step the limits give (dt_scale applied)
    EnergySummary energy;
    double wall_s = 0, element_cycles_per_s = 0;
    TimingSummary timing;
    std::vector<InterfaceSummary> interfaces;
    std::string text() const;
    nlohmann::json to_json() const;
    /// Removes from a to_json() summary what depends on the machine and its load, not on the model:
    /// wall time, element-cycles per second, threads, the timing table, the contact share and each
    /// interface's search and force times. Identical runs give identical results after it (the HDF5
    /// summary is written this way; tests/determinism compares runs.json with it).
    static void erase_machine_facts(nlohmann::json& summary);
};

class ExplicitSolver {
public:
    ExplicitSolver(ExplicitModel& model, ExplicitOptions options);
    ~ExplicitSolver();
    /// Runs to end_time. Throws SolverError on instability (NaN, energy growth, inverted element),
    /// InputError on a fixed step above critical.
    RunSummary run();
    /// Called at every history sample (after the sample is stored), or on its own schedule
    /// (ExplicitOptions::observer_interval), e.g. to probe the state or to end the run early with
    /// request_stop(). Also at the start and at the end state.
    std::function<void(const ExplicitSolver&)> observer;
    /// Ends the run after the current cycle (like LS-DYNA's sense switch "sw1"): for an observer
    /// that knows the event of interest is over, e.g. contact has ended. The summary's end_time is
    /// the time reached.
    void request_stop() const { stop_requested_ = true; }

    const NodalState& state() const { return s_; }
    const History& history() const { return history_; }
    double time() const { return t_; }
    long step() const { return step_; }
    /// Current critical step (Table 2-1, times the measured stability factor for solid groups;
    /// before the 0.9).
    double critical_dt() const { return dt_crit_; }
    /// 2/omega_max measured on the solid groups over their smallest Table 2-1 step (1 when not
    /// measured or above 1).
    double stability_factor() const { return stability_factor_; }
    /// omega_max of the solid groups measured at the start (0 when not measured).
    double measured_omega_max() const { return omega_max_; }
    /// Restart files written by this run so far (ExplicitOptions::restart_times/restart_interval).
    const std::vector<std::filesystem::path>& restart_files() const { return restart_files_; }
    /// The latest restart file of run `name` in `dir` (the highest step), e.g. to resume a killed
    /// run; InputError when there is none.
    static std::filesystem::path latest_restart(const std::filesystem::path& dir, std::string_view name);
    /// The restart files of run `name` in `dir`, oldest first (by step).
    static std::vector<std::filesystem::path> restart_files_in(const std::filesystem::path& dir, std::string_view name);
    /// Removes all but the newest `keep` restart files of run `name` in `dir` (a long run keeps
    /// only what a resumption needs; the newest is complete: each is written under a temporary name).
    static void remove_older_restarts(const std::filesystem::path& dir, std::string_view name, std::size_t keep);
    /// The model time a restart file holds (InputError when `path` is not one).
    static double restart_time(const std::filesystem::path& path);
    /// Writes the complete state to `path` (what the restart options do at their times).
    void write_restart(const std::filesystem::path& path) const;
    /// Largest element von Mises stress of part `part` at the last force evaluation (0 for a part
    /// without groups), for observers that watch every cycle; History::max_von_mises holds the
    /// maxima between history samples.
    double max_von_mises(std::string_view part) const;

private:
    void initialize();
    void compute_forces(bool compute_dt);
    void external_forces(double t);
    void record(bool force);
    void notify_observer(bool force);
    void start_fresh(double solid_table_dt);
    void restore(const std::filesystem::path& path);
    void restart_dumps();
    double choose_dt() const;
    void write_vtu(double t);
    /// Throws SolverError naming the time, cycle, element (bad_element of bad_group, else the one
    /// around the node with the largest kinetic energy), its part and the likely cause.
    [[noreturn]] void unstable(const std::string& why, int bad_group = -1, int bad_element = -1);
    std::string element_name(int group, int element) const;
    std::string block_element_name(int block, int element) const;

    ExplicitModel& model_;
    ExplicitOptions opt_;
    NodalState s_;
    History history_;
    RunSummary summary_;
    std::vector<Vec3> fext_, mext_, fprov_, mprov_;
    double w_prov_ = 0.0;
    std::vector<double> alpha_, alpha_rot_;   // per node / rotational slot
    std::vector<unsigned> fixed_;             // per node mask
    std::vector<unsigned char> constrained_;  // per node: any dof fixed or prescribed
    double t_ = 0.0;
    long step_ = 0;
    double stability_factor_ = 1.0, omega_max_ = 0.0;
    double measure_omega_max();
    std::vector<char> solid_;          // per group: measured by measure_omega_max
    std::vector<double> dt_factor_;    // per group: factor the solver applies to its step (1 when the group does)
    double dt_crit_ = 0.0;             // smallest critical step (stability factor applied)
    double dt_crit_unscaled_ = 0.0;    // the same element's step before the stability factor
    int dt_group_ = -1, dt_element_ = -1;
    // visc_power_: viscous power of the groups that do not add their viscous forces to s_.fv
    // (booked first-order); book_viscous_: s_.fv is allocated and booked in the update loop.
    double e_int_ = 0, e_hg_ = 0, visc_power_ = 0;
    // Per part (EnergySummary::parts): each group's part, and the parts' energies at the last force
    // evaluation.
    std::vector<int> group_part_;
    std::vector<double> part_int_, part_hg_;
    bool book_viscous_ = false;
    std::map<std::string, double> max_vm_;
    double next_history_ = 0.0, next_vtu_ = 0.0;
    double e_kin_ = 0, e_damp_ = 0, e_visc_ = 0, w_ext_ = 0, e0_ = 0, input_scale_ = 0;
    // The judged window (ExplicitOptions::health_from): entered yet, and the balance error there.
    bool health_started_ = false;
    double balance_at_from_ = 0.0;
    std::unique_ptr<io::PvdSeries> pvd_;
    double w_abs_ = 0.0;
    bool has_loads_ = false;
    double gravity_c_ = std::numeric_limits<double>::quiet_NaN();  // the gravity curve's value in fext_ (external_forces)
    std::vector<std::array<double, 3>> target_;  // prescribed velocity per constrained node (NaN: free)
    std::vector<int> target_index_;              // per node: index into target_, or -1
    long element_cycles_ = 0;
    mutable bool stop_requested_ = false;  // set by request_stop() from the observer
    // Loop state carried between cycles (and through restarts).
    double dt_half_ = 0.0, dt_prev_ = 0.0;  // the step to come and the last one
    double ctrl_min_ = 0.0;                 // smallest critical step so far, and its element
    int ctrl_group_ = -1, ctrl_element_ = -1;
    double next_observer_ = 0.0, last_observer_ = -1.0;
    std::vector<double> group_vm_;          // per group: largest von Mises at the last force evaluation
    TimingSummary timing_;
    bool restarted_ = false;                 // initialized from a restart file
    std::vector<double> restart_times_;      // sorted, those still to come
    double next_restart_ = 0.0;              // by restart_interval
    std::vector<std::filesystem::path> restart_files_;
    std::vector<double> provider_s_;        // per provider: wall time in add_forces
};

}  // namespace fem
