#pragma once
// The explicit solver's case file (TOML) for `fem-explicit case.toml [--output DIR] [--quiet]`: an
// LS-DYNA keyword deck's content (parts, materials, rigid parts and their motions, contact, boundary
// conditions, loads, gravity, outputs, control, restart) in a readable file. Every key, its unit and
// its default: lib/explicit_case/CASE_FILE.md. A small example (a bar struck at one end):
//
//   [control]
//   end_time = 1e-3                 # s
//   [output]
//   interval = 1e-5                 # histories (HDF5 + .dat)
//   [[output.node]]
//   name = "middle"
//   set = "bar.middle"
//   [[material]]
//   name = "steel"
//   E = 210e9
//   nu = 0.0
//   rho = 7800.0
//   [[part]]
//   name = "bar"
//   material = "steel"
//   mesh = "box"                    # box | finger | ellipsoid | gmsh | deck
//   size = [1.0, 0.02, 0.02]
//   elements = [100, 1, 1]
//   [[boundary]]
//   set = "x0-bar"                  # the box's node set x0 of part "bar"
//   fix = ["x", "y", "z"]
//   [[boundary]]
//   set = "x1-bar"
//   velocity = [1.0, 0.0, 0.0]      # m/s, times an optional curve
//
// A case with a [hand] table is a hand scene of thesis Ch 4 (drum + Table 4-1 fingers): it is built
// by lib/hand's HandModel from a hand::Scene (the football sweep's own builder), its deformable
// parts are ellipsoid objects and its rigid parts translating plates (CASE_FILE.md lists what a hand
// case accepts). Any other case is built here part by part.
//
// Reading is strict (lib/input): every key takes effect as written or is refused with
// "file:line: key: problem" (did-you-mean for misspelt keys and choices); reading never touches the
// mesh files, building the model does (its errors name the part and file).
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "check/run_health.hpp"
#include "contact/friction.hpp"
#include "explicit/solver.hpp"
#include "hand/scene.hpp"
#include "input/toml_input.hpp"
#include "material/elastic.hpp"
#include "mesh/ellipsoid.hpp"

namespace fem::explicit_case {

/// One [[part]]: a deformable body meshed by a generator or read from a file.
struct Part {
    std::string name;
    std::string mesh;              // box | finger | ellipsoid | gmsh | deck
    ElasticMaterial material;
    // box
    Vec3 size = Vec3::Zero(), origin = Vec3::Zero();
    std::array<int, 3> elements{1, 1, 1};
    std::string element = "hex8";  // box: hex8 | tet4 | tet10
    // finger: a Table 3-2 case ("A".."D") or a Table 4-1 finger ("A".."E"), root face at the origin
    std::string table_3_2_case, table_4_1_finger;
    /// ellipsoid: the whole object as lib/hand takes it (geometry, grid, half, material, mass,
    /// initial velocity, damping, and in a hand case its carriage); a hand case's objects are these.
    hand::EllipsoidObject ellipsoid;
    // gmsh / deck: every solid element of the file is this part
    std::filesystem::path file;
    Vec3 offset = Vec3::Zero();    // moves the mesh (box, finger, gmsh, deck)
    /// A hand case's box, gmsh or deck object cut by the half model's symmetry plane: the node set
    /// (the mesh's own name, e.g. a box's "z1") on that plane z = const (hand::MeshObject::symmetry_set).
    std::string symmetry_set;
    // solver settings
    double alpha = 0.0;            // mass damping [1/s] (Eq 2-39, *DAMPING_PART_MASS)
    /// A rigid part's name: alpha damps the velocity relative to that part's motion
    /// (explicit/relative_damping.hpp); empty: absolute velocity.
    std::string damping_frame;
    Vec3 initial_velocity = Vec3::Zero();
    double hourglass_qm = 0.1;     // hexahedra
    /// Table 2-1's bulk viscosity coefficients (*CONTROL_BULK_VISCOSITY Q1 = C0, Q2 = C1); both 0: none.
    BulkViscosity bulk{};
    int line = 0;                  // in the case file, for messages
};

/// One [[rigid_part]]: a prescribed rigid body (LS-DYNA *MAT_RIGID with motion).
struct RigidPart {
    std::string name;
    std::string mesh;              // plate | box | drum | gmsh
    /// plate: as lib/hand takes it (centre, edge vectors, segments, depth; direction and speed when
    /// its motion is one translation: a hand case's conveyor pallet).
    hand::Plate plate;
    // box
    Vec3 size = Vec3::Zero(), origin = Vec3::Zero();
    std::array<int, 3> elements{1, 1, 1};
    // drum (stepped cylinder about y through centre): levels [y_bottom, y_top, radius]
    Vec3 centre = Vec3::Zero();
    std::vector<hand::DrumLevel> levels;
    int drum_segments = 48;
    std::filesystem::path file;
    double depth = 0.03;           // deepest penetration taken as contact [m]
    bool track_approach_side = false;  // capture only nodes that come from in front (contact.hpp)
    /// The motion, composed in the order of the [[rigid_part.motion]] entries (the first innermost).
    RigidMotion motion;
    int line = 0;
};

/// One [[contact]] pair (lib/hand's pair: slave, master, friction, two_way for deformable masters,
/// penalty_scale = LS-DYNA SLSFAC), with its place in the file.
struct Contact : hand::ContactPair {
    int line = 0;
};

/// One [[rigid_wall]]: a fixed frictionless planar rigid wall (LS-DYNA *RIGIDWALL_PLANAR, penalty;
/// contact/rigid_wall.hpp) holding the surface nodes of deformable parts on its normal's side.
struct RigidWall {
    std::string name;              // pair name in outputs (default "<parts> on rigid-wall-<k>")
    Vec3 point = Vec3::Zero(), normal = Vec3::UnitZ();
    std::vector<std::string> slaves;  // deformable parts
    double penalty_scale = 0.1;    // LS-DYNA SLSFAC
    double depth = std::numeric_limits<double>::infinity();  // deepest penetration taken as contact [m]
    int line = 0;
};

/// One [[boundary]] entry: exactly one of fix, velocity, displacement, symmetry, follow.
struct Boundary {
    enum class Kind { fix, velocity, displacement, symmetry, follow };
    Kind kind = Kind::fix;
    std::string set;               // node set (every kind but a symmetry plane found by position)
    unsigned dofs = 0;             // fix
    Vec3 value = Vec3::Zero();     // velocity [m/s] or displacement [m], times curve
    Curve curve;
    Vec3 normal = Vec3::Zero(), point = Vec3::Zero();  // symmetry: plane normal (a global axis), a point on it
    std::string rigid_part;        // follow: the nodes move with this rigid part
    int line = 0;
};

/// One [[load]]: a force per node of a set, times a curve.
struct Load {
    std::string set;
    Vec3 force = Vec3::Zero();
    Curve curve;
    int line = 0;
};

struct HistoryNode {
    std::string name, set;         // the set's first node
};

struct Output {
    std::filesystem::path folder;  // default: <case stem>_results beside the case file
    double interval = 0.0;         // histories [s]; 0: every cycle
    double vtu_interval = 0.0;     // > 0: VTU/PVD every vtu_interval [s]
    bool h5 = true;                // histories.h5 (HDF5)
    std::vector<HistoryNode> nodes;
};

struct Control {
    double end_time = 0.0;
    double dt_scale = 0.9;
    int threads = 0;               // 0: the default (OMP_NUM_THREADS or all cores)
    std::vector<double> restart_times;
    double restart_interval = 0.0;
    std::filesystem::path restart_from;
    std::string name;              // run name (default: the case file's stem)
};

/// One [[phase]]: the run in stages, each restarting from the previous one's state at its start
/// (LS-DYNA's full deck restart), e.g. the grasp and the flip of thesis Sec 4.4.
struct Phase {
    std::string name;
    double start = 0.0;            // [s]; the first phase starts at 0
    std::vector<std::string> release;  // hand objects no longer carried from this phase on
    int line = 0;
};

struct ExplicitCase {
    std::string source;            // the case file (messages)
    std::filesystem::path base;    // its folder
    Control control;
    Output output;
    std::map<std::string, ElasticMaterial> materials;
    std::vector<Part> parts;
    std::vector<RigidPart> rigid_parts;
    std::vector<Contact> contacts;
    std::vector<RigidWall> rigid_walls;
    std::vector<Boundary> boundaries;
    std::vector<Load> loads;
    std::optional<std::pair<Vec3, Curve>> gravity;
    /// A [hand] case: the hand, its turn, damping frame and the other scene settings (objects,
    /// plates, contacts and gravity are the case's parts and keys; hand_scene puts them in).
    std::optional<hand::Scene> hand;
    std::vector<Phase> phases;     // empty: one run
    /// [[health_exemption]]: runs of the case allowed over a health limit, with the reason
    /// (check/run_health.hpp; judged as a study's reference file's are).
    std::vector<check::HealthExemption> health_exemptions;
    bool cut = false;  // ended early by cut_at (--end-time): an exemption's runs need not reach its limit
};

/// Reads and validates a case file (InputError "file:line: key: problem"), with `settings` replacing
/// values of the file before it is read (fem-explicit --set, a sweep's cases: input::Setting).
ExplicitCase read_case(const std::filesystem::path& path, const std::vector<input::Setting>& settings = {});
/// The same from text; `source` names it in messages, `base` is where relative paths start.
ExplicitCase parse_case(std::string_view text, const std::string& source, const std::filesystem::path& base = ".");

/// The hand scene of a case with [hand] (what HandModel builds); InputError for a case without.
hand::Scene hand_scene(const ExplicitCase& c);

/// Phase k of a case with [[phase]]s as a case of its own: its end time (the next phase's start, or
/// [control] end_time), the objects released up to it no longer carried, user restart times inside
/// it, its name "<name>-<phase>". The phases after the first restart from the previous one's state.
ExplicitCase phase_case(const ExplicitCase& c, std::size_t k);

/// Ends the case at t_end (fem-explicit --end-time: a short run of a long case): phases starting at
/// or after it and restart times from it on are dropped; the health exemptions still apply, but one
/// the shorter run does not need is not reported as stale. InputError for t_end <= 0.
void cut_at(ExplicitCase& c, double t_end);

/// The explicit model of a case: reads the meshes, builds parts, rigid parts, contact, boundary
/// conditions, loads and gravity. InputError naming the part, set or file for what cannot be built.
class CaseModel {
public:
    explicit CaseModel(const ExplicitCase& c);
    ~CaseModel();
    ExplicitModel& model() { return hand_ ? hand_->model() : *model_; }
    const Mesh& mesh() const { return hand_ ? hand_->mesh() : model_->mesh(); }
    /// The hand model of a [hand] case (nullptr otherwise).
    const hand::HandModel* hand_model() const { return hand_.get(); }
    /// Contact pair names "<slave> on <master>", in case-file order.
    const std::vector<std::string>& contact_pairs() const { return pairs_; }

private:
    std::unique_ptr<hand::HandModel> hand_;
    std::unique_ptr<ExplicitModel> model_;
    std::vector<std::string> pairs_;
};

/// The solver options of a case, with its output files under `folder` (the run's staging folder).
ExplicitOptions solver_options(const ExplicitCase& c, const CaseModel& m, const std::filesystem::path& folder);

/// The columns of the run's histories.dat and energies.dat (run_case writes them; a sweep's
/// [[result]]s read them): time_s, then <node>_ux_m, <node>_vx_m_per_s, ... y, z for each
/// [[output.node]]; time_s, kinetic_J, internal_J, hourglass_J, damping_J, viscous_J, external_J,
/// contact_J, balance_error_J.
std::vector<std::string> history_columns(const ExplicitCase& c);
const std::vector<std::string>& energy_columns();

/// What run_case did: its summary text (summary.txt) and the verdict line of every run whose health
/// failed (check/run_health.hpp: energy balance error above 1 % or hourglass energy above 10 % of
/// internal; fem-explicit then exits 1). The files of an unhealthy run are written all the same:
/// unlike an unstable run (SolverError, nothing written), it is a result the user must be able to
/// inspect.
/// Stale exemptions (a [[health_exemption]] that names no run of the case, or whose runs all met the
/// limit it exempts from) fail the case as well (fem-explicit exits 1), as in a study.
struct CaseOutcome {
    std::string summary;
    std::vector<std::string> unhealthy;
    std::vector<std::string> stale_exemptions;
    bool healthy() const { return unhealthy.empty() && stale_exemptions.empty(); }
};

/// Runs a case into c.output.folder as one io::RunFolder set (summary.txt, run.json,
/// histories.h5, histories.dat, energies.dat, VTU/PVD, restart dumps) and judges each run's health.
/// A case with [[phase]]s runs each phase into <folder>/<phase>/ (the same files), each after the
/// first restarting from the dump its predecessor wrote at its start, and a summary.txt of all.
/// quiet: no progress line. Ctrl-C: the state reached is written, marked partial (PARTIAL.txt), and
/// fem::Interrupted is thrown.
/// resume (fem-explicit --resume): continue the run that was killed (SIGKILL, a crash, a power cut)
/// in c.output.folder from the last restart dump it wrote, in its staging folder
/// (io::RunFolder::Leftovers::adopt); the set then equals an uninterrupted run's. With [[phase]]s the
/// phases it completed are kept and the one it was in continues. InputError when the folder holds no
/// killed run or its run wrote no dump.
CaseOutcome run_case(const ExplicitCase& c, bool quiet = false, bool resume = false);

}  // namespace fem::explicit_case
