#include "modal/case.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "assembly/model.hpp"
#include "core/error.hpp"
#include "input/toml_input.hpp"
#include "io/run_folder.hpp"
#include "mesh/gmsh.hpp"
#include "mesh/mesh.hpp"

namespace fem::modal {
namespace {

DofMask parse_dofs(const input::TomlTable& t, DofMask fallback) {
    if (!t.has("dofs")) return fallback;
    static const std::map<std::string, DofMask> names = {{"ux", dof_bit(UX)}, {"uy", dof_bit(UY)}, {"uz", dof_bit(UZ)},
                                                         {"rx", dof_bit(RX)}, {"ry", dof_bit(RY)}, {"rz", dof_bit(RZ)},
                                                         {"all", kAllDofs}};
    const auto list = t.choices("dofs", {"ux", "uy", "uz", "rx", "ry", "rz", "all"});
    if (list.empty()) t.fail("dofs", "must name at least one DOF (ux uy uz rx ry rz all)");
    DofMask m = 0;
    for (const auto& s : list) m |= names.at(s);
    return m;
}

// "; largest stiffness, smallest mass in part 'beam' (steel: E = 1e+308 Pa, nu = 0.3, rho = 7800 kg/m^3)":
// the parts (and their materials) that hold the extremes of the stiffness and mass diagonals.
std::string extremes(const Conditioning& cond, const AssembledSystem& sys, const Mesh& mesh, const ModalCase& c) {
    // Reduced DOF -> node, node -> part (the first block that uses it).
    std::vector<int> node_of_reduced(sys.size(), -1);
    for (int node = 0; node < sys.dofs.node_count(); ++node)
        for (int k = 0; k < sys.dofs.dofs(node); ++k) {
            const int reduced = sys.reduction.reduced_of_full[sys.dofs.dof(node, k)];
            if (reduced >= 0 && node_of_reduced[reduced] < 0) node_of_reduced[reduced] = node;
        }
    std::vector<int> block_of_node(mesh.node_count(), -1);
    for (int b = static_cast<int>(mesh.blocks.size()) - 1; b >= 0; --b)
        for (int n : mesh.blocks[b].connectivity) block_of_node[n] = b;
    std::vector<std::pair<std::string, std::string>> roles;  // part, roles (in order of first mention)
    for (const auto& [dof, role] : {std::pair{cond.dof_k_max, "largest stiffness"}, {cond.dof_k_min, "smallest stiffness"},
                                    {cond.dof_m_max, "largest mass"}, {cond.dof_m_min, "smallest mass"}}) {
        const int node = dof >= 0 ? node_of_reduced[dof] : -1;
        if (node < 0 || block_of_node[node] < 0) continue;
        const std::string& part = mesh.blocks[block_of_node[node]].part;
        auto it = std::find_if(roles.begin(), roles.end(), [&](const auto& r) { return r.first == part; });
        if (it == roles.end()) roles.emplace_back(part, role);
        else it->second += std::string(", ") + role;
    }
    std::string out;
    for (const auto& [part, role] : roles) {
        out += fmt::format("; {} in part '{}'", role, part);
        for (const CasePart& p : c.parts)
            if (p.name == part)
                out += fmt::format(" ({}: E = {:g} Pa, nu = {:g}, rho = {:g} kg/m^3{})", p.material.name,
                                   p.material.youngs_modulus, p.material.poissons_ratio, p.material.density,
                                   p.thickness > 0 ? fmt::format(", thickness {:g} m", p.thickness) : "");
    }
    return out;
}

}  // namespace

namespace {

ModalCase from_document(const input::TomlDocument& doc, const std::string& stem) {
    const input::TomlTable root = doc.root();
    root.allow({"mesh", "output", "modes", "shift_hz", "mass", "materials", "parts", "supports", "couplings"});
    ModalCase c;
    c.mesh = root.path("mesh");
    c.output = root.has("output") ? root.path("output") : doc.base() / (stem + "_modes");
    c.options.modes = root.integer_or<int>("modes", 10, {.min = 1});
    c.options.shift_hz = root.real_or("shift_hz", 0.0);
    c.mass = root.choice_or("mass", {"consistent", "lumped"}, "consistent") == "lumped" ? solid::MassKind::Lumped
                                                                                       : solid::MassKind::Consistent;

    std::map<std::string, ElasticMaterial> materials;
    if (const auto mats = root.optional_table("materials"))
        for (const auto& [name, t] : mats->entries()) {
            t.allow({"E", "nu", "rho"});
            materials.emplace(name, ElasticMaterial::make(name, t.real("E", input::Range::positive()),
                                                          t.real("nu", input::Range::open(-1.0, 0.5)),
                                                          t.real("rho", input::Range::positive())));
        }
    const auto parts = root.tables("parts");
    if (parts.empty()) root.fail("no [[parts]]: give each part of the mesh a material");
    for (const input::TomlTable& t : parts) {
        t.allow({"name", "material", "thickness"});
        CasePart p;
        p.name = t.string("name");
        const std::string mat = t.string("material");
        auto it = materials.find(mat);
        if (it == materials.end()) {
            std::vector<std::string> known;
            for (const auto& [name, m] : materials) known.push_back(name);
            t.fail("material", "'" + mat + "' is not defined under [materials]" + input::did_you_mean(mat, known));
        }
        p.material = it->second;
        p.thickness = t.real_or("thickness", 0.0, input::Range::positive());
        c.parts.push_back(p);
    }
    for (const input::TomlTable& t : root.tables("supports")) {
        t.allow({"set", "dofs"});
        c.supports.push_back({t.string("set"), parse_dofs(t, kAllDofs)});
    }
    for (const input::TomlTable& t : root.tables("couplings")) {
        t.allow({"set", "sets", "dofs"});
        CaseCoupling cp;
        if (t.has("sets") == t.has("set")) t.fail("give exactly one of set (one node set) and sets (two node sets)");
        if (t.has("sets")) {
            cp.sets = t.strings("sets");
            if (cp.sets.size() != 2) t.fail("sets", "must name two node sets (coincident node pairs)");
        } else {
            cp.sets.push_back(t.string("set"));
        }
        cp.dofs = parse_dofs(t, kTranslations);
        c.couplings.push_back(cp);
    }
    doc.finish();
    return c;
}

}  // namespace

ModalCase read_modal_case(const std::filesystem::path& path) {
    return from_document(input::TomlDocument::read(path), path.stem().string());
}

ModalCase parse_modal_case(std::string_view text, const std::string& source, const std::filesystem::path& base) {
    return from_document(input::TomlDocument::parse(text, source, base), std::filesystem::path(source).stem().string());
}

std::string run_modal_case(const ModalCase& c) {
    // The output folder is checked (writable, not in use by another run) before anything is solved;
    // the results replace the previous run's set only when they are all written.
    io::RunFolder out(c.output, "fem-modal");
    const Mesh mesh = read_gmsh(c.mesh);
    Model model(mesh);
    std::set<int> covered;
    for (const CasePart& p : c.parts) {
        std::vector<int> blocks;
        try {
            blocks = mesh.blocks_of_part(p.name);
        } catch (const InputError& e) {
            throw InputError("case part '" + p.name + "' is not a physical group with elements in " + c.mesh.string() + ": " + e.what());
        }
        if (p.thickness > 0) model.add_shell_part(p.name, p.thickness, p.material, c.mass);
        else model.add_solid_part(p.name, p.material, {.mass = c.mass});
        covered.insert(blocks.begin(), blocks.end());
    }
    for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b)
        if (!covered.count(b) && dimension(mesh.blocks[b].shape) > 0)
            throw InputError("mesh part '" + mesh.blocks[b].part + "' (" + std::string(to_string(mesh.blocks[b].shape)) +
                             " elements) has no entry in [[parts]]: give it a material");
    for (const CaseSupport& s : c.supports) model.fix_nodes(mesh.node_set(s.set), s.dofs);
    for (const CaseCoupling& cp : c.couplings) {
        if (cp.sets.size() == 2) model.couple_coincident(mesh.node_set(cp.sets[0]), mesh.node_set(cp.sets[1]), cp.dofs);
        else model.couple(mesh.node_set(cp.sets[0]), cp.dofs);
    }
    const AssembledSystem sys = model.assemble();
    // A solve that fails for numerical reasons names the parts and materials at the extremes of the
    // stiffness and mass diagonals (the inputs that make the problem ill-conditioned).
    const Conditioning cond(sys.stiffness, sys.mass);
    ModalResult r;
    try {
        r = solve_modes(sys, c.options);
    } catch (const SolverError& e) {
        throw SolverError(e.what() + extremes(cond, sys, mesh, c));
    } catch (const InputError& e) {
        if (cond.representable()) throw;
        throw InputError(e.what() + extremes(cond, sys, mesh, c));
    }
    write_results(out.staging(), mesh, sys, r);
    out.commit();
    return summary(sys, r) + "  results: " + c.output.string() + "/{frequencies.csv, modes.h5, modes.pvd}\n";
}

}  // namespace fem::modal
