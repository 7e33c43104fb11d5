// Building the explicit model of a case (CaseModel: a [hand] case through lib/hand's HandModel, any
// other part by part) and running it (run_case) into an io::RunFolder.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <iostream>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "check/run_health.hpp"
#include "contact/explicit_contact.hpp"
#include "contact/rigid_wall.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "deck/deck.hpp"
#include "explicit/parallel.hpp"
#include "explicit/relative_damping.hpp"
#include "explicit/tet_groups.hpp"
#include "explicit_case/case_file.hpp"
#include "io/atomic_file.hpp"
#include "io/run_folder.hpp"
#include "io/table.hpp"
#include "mesh/finger.hpp"
#include "mesh/gmsh.hpp"

namespace fem::explicit_case {
namespace {

// "case.toml:12: [[part]] 'bar': " before a message of the model builder.
std::string at(const ExplicitCase& c, int line, std::string_view what) { return fmt::format("{}:{}: {}: ", c.source, line, what); }

// Runs f; an InputError from it gets the case file's place in front.
template <class F>
auto located(const std::string& where, F&& f) {
    try {
        return f();
    } catch (const InputError& e) {
        throw InputError(where + e.what());
    }
}

// The solid blocks of a mesh file as one part `name` (lower-dimensional blocks dropped: their nodes
// are the solids' nodes); node sets renamed "<set>-<name>" (as HandModel names its parts' sets),
// unless rename_sets is false (a hand case's mesh object: HandModel renames them itself).
Mesh as_part(Mesh m, const std::string& name, bool keep_shells = false, bool rename_sets = true) {
    Mesh out;
    out.nodes = std::move(m.nodes);
    for (auto& b : m.blocks)
        if (dimension(b.shape) == 3 || (keep_shells && dimension(b.shape) == 2)) {
            b.part = name;
            out.blocks.push_back(std::move(b));
        }
    if (out.blocks.empty()) throw InputError("the mesh has no " + std::string(keep_shells ? "solid or shell" : "solid") + " elements");
    for (auto& [set, nodes] : m.node_sets) out.node_sets[rename_sets ? set + "-" + name : set] = std::move(nodes);
    return out;
}

// The mesh of a [[part]] (its generator or file, moved by `offset`), as part p.name.
Mesh part_mesh(const Part& p, bool rename_sets = true) {
    Mesh m;
    if (p.mesh == "box") {
        m = p.element == "hex8" ? box_hex8(p.size.x(), p.size.y(), p.size.z(), p.elements[0], p.elements[1], p.elements[2], p.name)
                                : box_tets(p.size.x(), p.size.y(), p.size.z(), p.elements[0], p.elements[1], p.elements[2],
                                           p.element == "tet4" ? ElementShape::Tet4 : ElementShape::Tet10, p.name);
        m.translate(p.origin);
    } else if (p.mesh == "finger") {
        if (!p.table_3_2_case.empty()) {
            for (const auto& mc : finger::table_3_2_cases())
                if (mc.id == p.table_3_2_case) m = finger::mesh_case(mc, p.name);
        } else {
            const hand::FingerMesh fm;
            for (const auto& row : hand::table_4_1())
                if (row.name == p.table_4_1_finger)
                    m = finger::hex_finger({fm.semi_major, fm.semi_minor, row.length}, finger::mapped_cross_section(fm.section),
                                           hand::finger_layers(fm, row.length), p.name);
        }
    } else if (p.mesh == "ellipsoid") {
        m = hex_ellipsoid(p.ellipsoid.semi_axes, p.ellipsoid.grid, p.ellipsoid.half, p.name);
        m.translate(p.ellipsoid.centre);
        return as_part(std::move(m), p.name, false, rename_sets);
    } else if (p.mesh == "gmsh") {
        m = read_gmsh(p.file);
    } else {
        m = deck::read_deck(p.file).mesh;
    }
    m.translate(p.offset);
    return as_part(std::move(m), p.name, false, rename_sets);
}

Mesh rigid_mesh(const RigidPart& r) {
    if (r.mesh == "plate") return parallelogram_quad4(r.plate.centre, r.plate.u, r.plate.v, r.plate.nu, r.plate.nv, r.name);
    Mesh m;
    if (r.mesh == "box") {
        m = box_hex8(r.size.x(), r.size.y(), r.size.z(), r.elements[0], r.elements[1], r.elements[2], r.name);
        m.translate(r.origin);
    } else if (r.mesh == "drum") {
        hand::Drum d;
        d.centre = r.centre;
        d.levels = r.levels;
        m = hand::drum_mesh(d, r.drum_segments);
    } else {
        m = read_gmsh(r.file);
    }
    return as_part(std::move(m), r.name, true);
}

}  // namespace

hand::Scene hand_scene(const ExplicitCase& c) {
    if (!c.hand) throw InputError(c.source + ": the case has no [hand]");
    hand::Scene s = *c.hand;
    for (const Part& p : c.parts) {
        if (p.mesh == "ellipsoid") {
            s.objects.push_back(p.ellipsoid);
            continue;
        }
        // A box, Gmsh or deck object (the chicken of Ch 5 is one in C++, or a user's own object):
        // lib/hand's MeshObject, its node sets under their own names (HandModel appends "-<part>").
        hand::MeshObject o;
        o.part = p.name;
        o.mesh = located(at(c, p.line, "[[part]] '" + p.name + "'"), [&] { return part_mesh(p, false); });
        o.material = p.material;
        o.initial_velocity = p.initial_velocity;
        o.alpha = p.alpha;
        o.hourglass_qm = p.hourglass_qm;
        o.bulk = p.bulk;
        o.symmetry_set = p.symmetry_set;
        if (!o.symmetry_set.empty() && !o.mesh.node_sets.count(o.symmetry_set)) {
            std::vector<std::string> known;
            for (const auto& [name, nodes] : o.mesh.node_sets) known.push_back(name);
            throw InputError(at(c, p.line, "[[part]] '" + p.name + "'") +
                             fmt::format("symmetry_set: '{}' is not a node set of its mesh (it has: {})", o.symmetry_set,
                                         known.empty() ? std::string("none") : fmt::format("{}", fmt::join(known, ", "))));
        }
        s.meshes.push_back(std::move(o));
    }
    for (const RigidPart& r : c.rigid_parts) s.plates.push_back(r.plate);
    for (const Contact& k : c.contacts) s.contacts.push_back(k);
    if (c.gravity) {
        s.gravity = c.gravity->first;
        s.gravity_curve = c.gravity->second;
    }
    return s;
}

CaseModel::~CaseModel() = default;

CaseModel::CaseModel(const ExplicitCase& c) {
    for (const Contact& k : c.contacts) pairs_.push_back(k.slave + " on " + k.master);
    if (c.hand) {
        hand_ = std::make_unique<hand::HandModel>(hand_scene(c));
        return;
    }
    Mesh mesh;
    for (const Part& p : c.parts) mesh.append(located(at(c, p.line, "[[part]] '" + p.name + "'"), [&] { return part_mesh(p); }));
    for (const RigidPart& r : c.rigid_parts)
        mesh.append(located(at(c, r.line, "[[rigid_part]] '" + r.name + "'"), [&] { return rigid_mesh(r); }));
    model_ = std::make_unique<ExplicitModel>(std::move(mesh));
    ExplicitModel& model = *model_;
    const Mesh& msh = model.mesh();
    std::map<std::string, std::vector<int>> part_nodes;
    for (const Part& p : c.parts) {
        located(at(c, p.line, "[[part]] '" + p.name + "'"), [&] {
            std::set<ElementShape> shapes;
            for (int b : msh.blocks_of_part(p.name)) shapes.insert(msh.blocks[b].shape);
            part_nodes[p.name] = msh.nodes_of_part(p.name);
            ElasticMaterial material = p.material;
            const double mass = p.mesh == "ellipsoid" ? p.ellipsoid.mass : 0.0;
            if (mass > 0.0) {  // the density that gives the part this mass on its mesh (as HandModel does)
                double volume = 0.0;
                for (int b : msh.blocks_of_part(p.name))
                    for (int e = 0; e < msh.blocks[b].size(); ++e)
                        volume += contact::element_volume(msh.blocks[b].shape, msh.element_coordinates(b, e));
                material = ElasticMaterial::make(material.name, material.youngs_modulus, material.poissons_ratio, mass / volume);
            }
            const bool bulk_on = p.bulk.quadratic > 0.0 || p.bulk.linear > 0.0;
            if (shapes == std::set{ElementShape::Hex8}) {
                model.add_hex8(p.name, material, {.hourglass_qm = p.hourglass_qm, .bulk_viscosity = bulk_on, .bulk = p.bulk});
            } else if (std::all_of(shapes.begin(), shapes.end(), [](ElementShape s) { return s == ElementShape::Tet4 || s == ElementShape::Tet10; })) {
                add_tets(model, p.name, material, {.bulk_viscosity = bulk_on, .bulk = p.bulk});
            } else {
                std::string names;
                for (ElementShape s : shapes) names += (names.empty() ? "" : ", ") + std::string(to_string(s));
                throw InputError("the explicit solver takes hex8 (one-point), tet4 or tet10 solids in a part, one family "
                                 "per part; this one has " + names);
            }
            if (p.alpha > 0.0) model.set_mass_damping(p.name, p.alpha);
            if (p.initial_velocity.norm() > 0.0) model.set_initial_velocity(part_nodes[p.name], p.initial_velocity);
            return 0;
        });
    }
    std::map<std::string, RigidMotion> motion;
    for (const RigidPart& r : c.rigid_parts) {
        located(at(c, r.line, "[[rigid_part]] '" + r.name + "'"), [&] {
            model.add_rigid_part(r.name, r.motion);
            return 0;
        });
        motion[r.name] = r.motion;
    }
    for (const Part& p : c.parts)
        if (!p.damping_frame.empty())
            located(at(c, p.line, "[[part]] '" + p.name + "'"), [&] {
                set_relative_mass_damping(model, p.name, p.alpha, motion.at(p.damping_frame), p.damping_frame);
                return 0;
            });
    for (std::size_t k = 0; k < c.boundaries.size(); ++k) {
        const Boundary& b = c.boundaries[k];
        located(at(c, b.line, fmt::format("boundary[{}]", k)), [&] {
            if (b.kind == Boundary::Kind::symmetry && b.set.empty()) {
                model.add_symmetry_plane(b.normal, b.point);
                return 0;
            }
            const std::vector<int>& nodes = msh.node_set(b.set);
            switch (b.kind) {
            case Boundary::Kind::fix: model.fix(nodes, Dofs::of(b.dofs)); break;
            case Boundary::Kind::velocity:
                for (int d = 0; d < 3; ++d) model.prescribe_velocity(nodes, d, b.value[d], b.curve);
                break;
            case Boundary::Kind::displacement:
                for (int d = 0; d < 3; ++d) model.prescribe_displacement(nodes, d, b.value[d], b.curve);
                break;
            case Boundary::Kind::symmetry: model.add_symmetry_plane(b.normal, nodes); break;
            case Boundary::Kind::follow: model.prescribe_motion(nodes, motion.at(b.rigid_part)); break;
            }
            return 0;
        });
    }
    for (std::size_t k = 0; k < c.loads.size(); ++k) {
        const Load& l = c.loads[k];
        located(at(c, l.line, fmt::format("load[{}]", k)), [&] {
            model.add_nodal_force(msh.node_set(l.set), l.force, l.curve);
            return 0;
        });
    }
    if (c.gravity) model.set_gravity(c.gravity->first, c.gravity->second);
    for (std::size_t k = 0; k < c.contacts.size(); ++k) {
        const Contact& ct = c.contacts[k];
        located(at(c, ct.line, fmt::format("contact[{}]", k)), [&] {
            auto material_of = [&](const std::string& part) {
                for (const Part& p : c.parts)
                    if (p.name == part) return p.material;
                throw InputError("no deformable part '" + part + "'");
            };
            contact::ContactOptions opt;
            opt.friction = ct.friction;
            opt.penalty_scale = ct.penalty_scale;
            auto slave = contact::ContactSurface::from_part(msh, ct.slave, material_of(ct.slave));
            const auto rigid = std::find_if(c.rigid_parts.begin(), c.rigid_parts.end(), [&](const RigidPart& r) { return r.name == ct.master; });
            if (rigid != c.rigid_parts.end()) {
                auto master = contact::ContactSurface::rigid_part(msh, ct.master, rigid->depth);
                opt.track_approach_side = rigid->track_approach_side;
                contact::add_contact(model, contact::ContactInterface(pairs_[k], std::move(slave), std::move(master), opt));
            } else {
                opt.two_way = ct.two_way;
                auto master = contact::ContactSurface::from_part(msh, ct.master, material_of(ct.master));
                contact::add_contact(model, contact::ContactInterface(pairs_[k], std::move(slave), std::move(master), opt));
            }
            return 0;
        });
    }
    for (std::size_t k = 0; k < c.rigid_walls.size(); ++k) {
        const RigidWall& w = c.rigid_walls[k];
        located(at(c, w.line, fmt::format("rigid_wall[{}]", k)), [&] {
            std::vector<contact::ContactSurface> each;
            for (const std::string& part : w.slaves)
                for (const Part& p : c.parts)
                    if (p.name == part) each.push_back(contact::ContactSurface::from_part(msh, part, p.material));
            contact::add_rigid_wall(model, contact::PlanarWall(w.name, w.point, w.normal,
                                                               contact::ContactSurface::merge(w.name, each),
                                                               {w.penalty_scale, w.depth}));
            return 0;
        });
        pairs_.push_back(w.name);
    }
}

ExplicitOptions solver_options(const ExplicitCase& c, const CaseModel& m, const std::filesystem::path& folder) {
    ExplicitOptions o;
    o.end_time = c.control.end_time;
    o.dt_scale = c.control.dt_scale;
    o.name = c.control.name;
    o.history_interval = c.output.interval;
    for (const HistoryNode& h : c.output.nodes) {
        const std::vector<int>& nodes = located(c.source + ": output node '" + h.name + "': ", [&] { return m.mesh().node_set(h.set); });
        if (nodes.empty()) throw InputError(c.source + ": output node '" + h.name + "': node set '" + h.set + "' is empty");
        o.history_nodes.push_back({h.name, nodes.front()});
    }
    if (c.output.h5) o.h5_path = folder / "histories.h5";
    if (c.output.vtu_interval > 0.0) {
        o.pvd_path = folder / "results.pvd";
        o.vtu_interval = c.output.vtu_interval;
    }
    o.restart_times = c.control.restart_times;
    o.restart_interval = c.control.restart_interval;
    o.restart_dir = folder;
    o.restart_from = c.control.restart_from;
    o.print_summary = false;
    return o;
}

namespace {
// A history node's column: its name, u or v, the axis, the unit.
std::string node_column(const std::string& node, char quantity, int axis) {
    return fmt::format("{}_{}{}_{}", node, quantity, "xyz"[axis], quantity == 'u' ? "m" : "m_per_s");
}
}  // namespace

std::vector<std::string> history_columns(const ExplicitCase& c) {
    std::vector<std::string> columns{"time_s"};
    for (const HistoryNode& n : c.output.nodes)
        for (int d = 0; d < 3; ++d) columns.insert(columns.end(), {node_column(n.name, 'u', d), node_column(n.name, 'v', d)});
    return columns;
}

const std::vector<std::string>& energy_columns() {
    static const std::vector<std::string> columns{"time_s",    "kinetic_J", "internal_J", "hourglass_J",    "damping_J",
                                                  "viscous_J", "external_J", "contact_J", "balance_error_J"};
    return columns;
}

namespace {

void write_histories(const std::filesystem::path& dir, const History& h) {
    io::Table nodes;
    nodes.add("time_s", h.time);
    for (const auto& n : h.nodes) {
        for (int d = 0; d < 3; ++d) {
            std::vector<double> u, v;
            for (const Vec3& x : n.displacement) u.push_back(x[d]);
            for (const Vec3& x : n.velocity) v.push_back(x[d]);
            nodes.add(node_column(n.name, 'u', d), u);
            nodes.add(node_column(n.name, 'v', d), v);
        }
    }
    io::write_dat(dir / "histories.dat", nodes);
    const std::vector<std::vector<double>> energies{h.time,    h.kinetic,  h.internal, h.hourglass, h.damping,
                                                    h.viscous, h.external, h.contact,  h.balance};
    io::Table e;
    for (std::size_t i = 0; i < energies.size(); ++i) e.add(energy_columns()[i], energies[i]);
    io::write_dat(dir / "energies.dat", e);
    if (!h.max_von_mises.empty()) {  // element histories: the largest von Mises stress of each part
        io::Table vm;
        vm.add("time_s", h.time);
        for (const auto& [part, values] : h.max_von_mises) vm.add(part + "_max_von_mises_Pa", values);
        io::write_dat(dir / "von_mises.dat", vm);
    }
}

}  // namespace

namespace {

// One run of a case into `dir` (summary.txt, run.json, histories, VTU, restart dumps); the restart
// dumps it wrote are added to `dumps`, its health verdict to `judged` (and to `unhealthy` if failed).
// `interrupted`: Ctrl-C's message (the state reached is written, marked partial; not judged).
std::string run_into(const ExplicitCase& c, const std::filesystem::path& dir, const std::filesystem::path& shown, bool quiet,
                     std::vector<std::filesystem::path>& dumps, std::vector<check::RunHealth>& judged,
                     std::vector<std::string>& unhealthy, std::string& interrupted) {
    std::filesystem::create_directories(dir);
    CaseModel m(c);
    ExplicitOptions opt = solver_options(c, m, dir);
    opt.progress = !quiet;
    ExplicitSolver solver(m.model(), opt);
    RunSummary s;
    try {
        s = solver.run();
    } catch (const Interrupted& e) {
        interrupted = e.what();  // the solver wrote its HDF5/VTU for the state reached, marked partial
    }
    dumps.insert(dumps.end(), solver.restart_files().begin(), solver.restart_files().end());
    write_histories(dir, solver.history());
    std::string text;
    if (!interrupted.empty()) {
        io::write_text_file(dir / "PARTIAL.txt", interrupted + "\n");
        text = interrupted + "\n";
    } else {
        nlohmann::json j = s.to_json();
        text = s.text();
        if (const auto h = check::judge_run_into(s.name, j, c.health_exemptions, judged, unhealthy)) {
            text += "health: " + h->text() + "\n";
            // A limit passed through the case file's exemption: its reason beside the verdict.
            for (const auto& [ok, why] : {std::pair{h->balance_ok, h->balance_exemption}, std::pair{h->hourglass_ok, h->hourglass_exemption}})
                if (!ok && !why.empty()) text += "health exemption: " + why + "\n";
            j["health"] = h->to_json();
        }
        io::write_text_file(dir / "run.json", j.dump(2) + "\n");
    }
    text += "results: " + shown.string() + "/{summary.txt, run.json, histories.dat, energies.dat, von_mises.dat" +
            (c.output.h5 ? ", histories.h5" : "") + (c.output.vtu_interval > 0 ? ", results.pvd" : "") + "}\n";
    io::write_text_file(dir / "summary.txt", text);
    return text;
}

}  // namespace

namespace {

// The restart dump a resumed run (or phase `name`) starts from: the last one the killed run wrote in
// `dir`, in its staging folder, which `out` adopted (LS-DYNA's `r=d3dump01`, found by itself).
std::filesystem::path resume_point(const ExplicitCase& c, const io::RunFolder& out, const std::filesystem::path& dir,
                                   const std::string& name) {
    const std::string folder = c.output.folder.string();
    if (!out.adopted())
        throw InputError(fmt::format("--resume: no killed run to resume in '{}' (a run that is killed leaves its "
                                     "files, restart dumps included, in a '.run-*' folder there; there is none): "
                                     "run the case without --resume",
                                     folder));
    try {
        return ExplicitSolver::latest_restart(dir, name);
    } catch (const InputError&) {
        throw InputError(fmt::format("--resume: the run killed in '{}' wrote no restart dump of run '{}' before it "
                                     "ended ([control] restart_interval or restart_times make it write them): run "
                                     "the case without --resume",
                                     folder, name));
    }
}

}  // namespace

CaseOutcome run_case(const ExplicitCase& c, bool quiet, bool resume) {
    // The output folder is checked (writable, not in use) before the model is built; the run's files
    // replace the previous set only when all are written.
    io::RunFolder out(c.output.folder, "fem-explicit", resume ? io::RunFolder::Leftovers::adopt : io::RunFolder::Leftovers::remove);
    if (c.control.threads > 0) par::set_threads(c.control.threads);
    std::string text, interrupted;
    std::vector<std::string> unhealthy;
    std::vector<check::RunHealth> judged;
    std::vector<std::filesystem::path> dumps;
    if (c.phases.empty() && resume) {
        ExplicitCase resumed = c;
        resumed.control.restart_from = resume_point(c, out, out.staging(), c.control.name);
        if (!quiet) std::cerr << "fem-explicit: resuming from " << resumed.control.restart_from.string() << '\n';
        text = run_into(resumed, out.staging(), c.output.folder, quiet, dumps, judged, unhealthy, interrupted);
    } else if (c.phases.empty()) {
        text = run_into(c, out.staging(), c.output.folder, quiet, dumps, judged, unhealthy, interrupted);
    } else {
        // Phase k runs to the next phase's start and writes a dump there; phase k + 1 restarts from it
        // with its own model (objects released), as the thesis's flip restarts from the grasp.
        // Resumed: the phases the killed run completed are taken as they are (their summary, health
        // verdict and last dump), the first it did not complete continues from its own last dump.
        const auto header = [&](std::size_t k, const ExplicitCase& p) {
            return fmt::format("== phase '{}' ({} to {} s) ==\n", c.phases[k].name, c.phases[k].start, p.control.end_time);
        };
        std::size_t first = 0;
        std::filesystem::path resume_from;
        for (; resume && first < c.phases.size(); ++first) {
            const ExplicitCase p = phase_case(c, first);
            const std::filesystem::path dir = out.staging() / c.phases[first].name;
            if (!out.adopted() || !std::filesystem::exists(dir / "summary.txt")) {  // run_into writes it last
                // The first phase the killed run did not complete: from its own last dump, else (killed
                // before that) from the previous phase's last dump, as an uninterrupted run would.
                try {
                    resume_from = resume_point(c, out, dir, p.control.name);
                } catch (const InputError&) {
                    if (first == 0 || !out.adopted()) throw;
                }
                if (!quiet && !resume_from.empty()) std::cerr << "fem-explicit: resuming from " << resume_from.string() << '\n';
                break;
            }
            std::ifstream summary(dir / "summary.txt"), run(dir / "run.json");
            text += header(first, p) + std::string((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
            check::judge_run_into(p.control.name, nlohmann::json::parse(run), c.health_exemptions, judged, unhealthy);
            if (first + 1 < c.phases.size()) dumps.push_back(ExplicitSolver::latest_restart(dir, p.control.name));
        }
        for (std::size_t k = first; k < c.phases.size() && interrupted.empty(); ++k) {
            ExplicitCase p = phase_case(c, k);
            if (k == first && !resume_from.empty()) {
                p.control.restart_from = resume_from;
            } else if (k > 0) {
                if (dumps.empty()) throw SolverError(fmt::format("{}: phase '{}' has no dump to start from", c.source, c.phases[k].name));
                p.control.restart_from = dumps.back();
            }
            if (k + 1 < c.phases.size()) p.control.restart_times.push_back(c.phases[k + 1].start);
            const std::size_t before = dumps.size();
            text += header(k, p);
            text += run_into(p, out.staging() / c.phases[k].name, c.output.folder / c.phases[k].name, quiet, dumps, judged,
                             unhealthy, interrupted);
            if (k + 1 < c.phases.size() && interrupted.empty() && dumps.size() == before)
                throw SolverError(fmt::format("{}: phase '{}' wrote no restart dump at {} s", c.source, c.phases[k].name, c.phases[k + 1].start));
        }
        io::write_text_file(out.staging() / "summary.txt", text);
    }
    // An exemption that names no run of the case, or whose runs all met the limit, is reported as a
    // study's is: stale exemptions get removed (not on a run cut short by --end-time).
    std::vector<std::string> stale;
    if (interrupted.empty() && !c.cut) stale = check::stale_exemptions(judged, c.health_exemptions, c.source);
    out.commit();
    if (!interrupted.empty()) throw Interrupted(interrupted + "; the state reached is in " + c.output.folder.string());
    return {text, unhealthy, stale};
}

}  // namespace fem::explicit_case
