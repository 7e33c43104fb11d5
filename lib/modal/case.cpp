#include "modal/case.hpp"

#include <algorithm>
#include <cctype>
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
#include "modal/deck_run.hpp"
#include "input/numbers.hpp"

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

// "; or the problem is ill-conditioned: part 'beam' (steel) has nu = 0.4999999999, ...": the parts
// whose Poisson's ratio makes the bulk stiffness swamp the shear stiffness that the low modes need
// (lambda / mu = 2 nu / (1 - 2 nu) above 1e6): their low eigenvalues sink into the round-off of the
// largest K_ii / M_ii and look like rigid-body modes. Empty when no part is that close to 0.5.
std::string nearly_incompressible(const ModalCase& c) {
    std::string out;
    for (const CasePart& p : c.parts) {
        const double nu = p.material.poissons_ratio, ratio = 2 * nu / (1 - 2 * nu);
        if (ratio > 1e6)
            out += fmt::format("{} part '{}' ({}) has nu = {:.12g}: lambda / mu = {:.3g}, nearly incompressible, so its bulk "
                               "stiffness swamps the shear stiffness of the low modes; use nu <= 0.49999",
                               out.empty() ? "; or the problem is ill-conditioned:" : ";", p.name, p.material.name, nu, ratio);
    }
    return out;
}

}  // namespace

namespace {

ModalCase from_document(const input::TomlDocument& doc, const std::string& stem) {
    const input::TomlTable root = doc.root();
    root.allow({"mesh", "output", "modes", "shift_hz", "mass", "tet_mass_rule", "shapes", "materials", "parts", "supports",
                "couplings"});
    ModalCase c;
    c.mesh = root.path("mesh");
    c.output = root.has("output") ? root.path("output") : doc.base() / (stem + "_modes");
    c.options.modes = root.integer_or<int>("modes", 10, {.min = 1});
    c.options.shift_hz = root.real_or("shift_hz", 0.0);
    c.mass = root.choice_or("mass", {"consistent", "lumped"}, "consistent") == "lumped" ? solid::MassKind::Lumped
                                                                                       : solid::MassKind::Consistent;
    c.tet_mass_rule_as_ccx = root.choice_or("tet_mass_rule", {"exact", "ccx"}, "exact") == "ccx";
    c.shapes = root.has("shapes") ? root.integer<int>("shapes", {.min = 0}) : -1;
    if (c.shapes > c.options.modes) root.fail("shapes", fmt::format("must be <= modes ({}), got {}", c.options.modes, c.shapes));

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
        t.allow({"name", "material", "thickness", "element"});
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
        if (t.has("element")) {
            p.element = t.choice("element", {"C3D8I", "C3D8", "C3D20", "C3D20R", "C3D10", "C3D4", "S4"});
            if ((p.element == "S4") != (p.thickness > 0))
                t.fail("element", p.element == "S4" ? "S4 shells need a thickness" : "a part with a thickness is a shell (S4)");
        }
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

namespace {

// The deck element type of every block of part p (its `element` key or the default of the shape).
std::string element_type(const CasePart& p, const ElementBlock& block) {
    const std::vector<std::string> types = element_types_for(block.shape);
    if (p.thickness > 0 && block.shape != ElementShape::Quad4)
        throw InputError("part '" + p.name + "' has a thickness (a shell part) but " + std::string(to_string(block.shape)) +
                         " elements; shells are quad4 (MITC4)");
    if (types.empty())
        throw InputError("part '" + p.name + "': no element formulation for " + std::string(to_string(block.shape)) +
                         " elements in a modal model (hex8, tet4, tet10 solids and quad4 shells)");
    if (block.shape == ElementShape::Quad4 && !(p.thickness > 0))
        throw InputError("part '" + p.name + "' has quad4 elements: give it a thickness (a shell part)");
    if (p.element.empty()) return types.front();
    if (std::find(types.begin(), types.end(), p.element) == types.end())
        throw InputError("part '" + p.name + "': element = \"" + p.element + "\" does not fit its " +
                         std::string(to_string(block.shape)) + " elements (" + input::one_of(types) + ")");
    return p.element;
}

}  // namespace

SolidOptions solid_options(const ModalCase& c) {
    SolidOptions o;
    o.mass = c.mass;
    if (c.tet_mass_rule_as_ccx) {
        o.tet10_mass_rule = solid::Tet10MassRule::FourPoint;
        o.tet4_mass_rule = solid::Tet4MassRule::Centroid;
    }
    return o;
}

void build_case_model(const ModalCase& c, const Mesh& mesh, Model& model) {
    std::set<int> covered;
    for (const CasePart& p : c.parts) {
        std::vector<int> blocks;
        try {
            blocks = mesh.blocks_of_part(p.name);
        } catch (const InputError& e) {
            throw InputError("case part '" + p.name + "' is not a physical group with elements in " + c.mesh.string() + ": " + e.what());
        }
        for (int b : blocks) {
            const std::string type = element_type(p, mesh.blocks[b]);
            add_element_block(model, b, type, p.material, p.thickness, solid_options(c));
        }
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
}

std::string run_modal_case(const ModalCase& c) {
    // The output folder is checked (writable, not in use by another run) before anything is solved;
    // the results replace the previous run's set only when they are all written.
    io::RunFolder out(c.output, "fem-modal");
    const Mesh mesh = read_gmsh(c.mesh);
    Model model(mesh);
    build_case_model(c, mesh, model);
    const AssembledSystem sys = model.assemble();
    // A solve that fails for numerical reasons names the parts and materials at the extremes of the
    // stiffness and mass diagonals (the inputs that make the problem ill-conditioned).
    const Conditioning cond(sys.stiffness, sys.mass);
    ModalResult r;
    try {
        r = solve_modes(sys, c.options);
    } catch (const SolverError& e) {
        throw SolverError(e.what() + extremes(cond, sys, mesh, c) + nearly_incompressible(c));
    } catch (const InputError& e) {
        if (!cond.representable()) throw InputError(e.what() + extremes(cond, sys, mesh, c));
        const std::string hint = nearly_incompressible(c);
        if (hint.empty()) throw;
        throw InputError(e.what() + hint);
    }
    if (c.shapes > c.options.modes)
        throw InputError(fmt::format("shapes = {} asks for more mode shapes than the {} modes computed", c.shapes, c.options.modes));
    write_results(out.staging(), mesh, sys, r, c.shapes);
    out.commit();
    return summary(sys, r) + "  results: " + c.output.string() + "/{frequencies.csv, modes.h5" +
           (c.shapes == 0 ? "" : ", modes.pvd") + "}\n";
}

std::string export_case_deck(const ModalCase& c, const std::filesystem::path& path) {
    const Mesh mesh = read_gmsh(c.mesh);
    Model model(mesh);
    build_case_model(c, mesh, model);  // refuses what the run would refuse
    deck::Deck d;
    d.mesh = mesh;
    d.mesh.node_sets.clear();
    std::string notes;
    // One *ELEMENT block and section per mesh block (element set = the part name).
    std::set<std::string> used_materials;
    for (const CasePart& p : c.parts)
        for (int b : mesh.blocks_of_part(p.name)) {
            const std::string type = element_type(p, mesh.blocks[b]);
            d.block_types.push_back(type);
            d.block_section.push_back(static_cast<int>(d.sections.size()));
            d.mesh.blocks[b].part = p.name;
            std::string elset = fmt::format("{}_{}", p.name, b);  // a deck name: letters, digits, '_'
            for (char& ch : elset)
                if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
            d.sections.push_back({p.thickness > 0 ? deck::Section::Shell : deck::Section::Solid, elset,
                                  p.material.name, p.thickness});
            d.materials.emplace(p.material.name, p.material);
            if ((type == "C3D10" || type == "C3D4") && !c.tet_mass_rule_as_ccx && c.mass == solid::MassKind::Consistent)
                notes += "note: part '" + p.name + "': ccx integrates the " + type + " mass with the stiffness rule, this case "
                         "with the exact rule (tet_mass_rule = \"ccx\" matches ccx; the frequencies differ by up to 1e-3 for "
                         "C3D10 and by percents for C3D4 on coarse meshes)\n";
            if (type == "S4")
                notes += "note: part '" + p.name + "': ccx expands S4 shells into C3D8I bricks, this case uses MITC4 shells "
                         "(different formulations; the frequencies differ by up to about 1 % on converged meshes)\n";
            if (c.mass == solid::MassKind::Lumped)
                notes += "note: ccx uses the consistent mass; this case asks for the lumped mass\n";
        }
    // Blocks in part order: rebuild the mesh's block list to follow the sections.
    std::vector<ElementBlock> blocks;
    for (const CasePart& p : c.parts)
        for (int b : mesh.blocks_of_part(p.name)) blocks.push_back(mesh.blocks[b]);
    d.mesh.blocks = blocks;
    // DOFs each node carries (6 where a shell touches it): a support of "all" fixes only those.
    std::vector<DofMask> carried(mesh.node_count(), 0);
    for (std::size_t b = 0; b < d.mesh.blocks.size(); ++b)
        for (int n : d.mesh.blocks[b].connectivity) carried[n] |= dofs_per_node(d.block_types[b]) == 6 ? kAllDofs : kTranslations;
    for (auto [node, mask] : model.constraints().fixes()) {
        mask &= carried[node];
        // Contiguous runs of components -> first, last DOF lines.
        for (int a = 0; a < 6; ++a) {
            if (!(mask & (1u << a))) continue;
            int e = a;
            while (e + 1 < 6 && (mask & (1u << (e + 1)))) ++e;
            d.boundaries.push_back({node, a + 1, e + 1});
            a = e;
        }
    }
    // A coupled set of nodes n0, n1, ... -> u_ni = u_n0 for every component (ni the dependent DOF,
    // as ccx wants each dependent DOF in one equation only).
    for (const auto& [nodes, mask] : model.constraints().couplings())
        for (int comp = 0; comp < 6; ++comp)
            if (mask & (1u << comp))
                for (std::size_t i = 1; i < nodes.size(); ++i) d.equations.push_back({nodes[i], nodes[0], comp + 1});
    d.frequency = deck::Frequency{c.options.modes};
    deck::write_deck(path, d, "fem-modal export of " + c.mesh.filename().string());
    if (c.options.shift_hz != 0.0)
        notes += fmt::format("note: the case's shift_hz = {:g} is not written (ccx finds the lowest modes itself)\n", c.options.shift_hz);
    return "wrote " + path.string() + "\n" + notes;
}

}  // namespace fem::modal
