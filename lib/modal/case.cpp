#include "modal/case.hpp"

#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "assembly/model.hpp"
#include "core/error.hpp"
#include "mesh/gmsh.hpp"
#include "mesh/mesh.hpp"

namespace fem::modal {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
    throw InputError(file.string() + ": " + what);
}

DofMask parse_dofs(const toml::node_view<const toml::node>& v, DofMask fallback, const std::filesystem::path& file,
                   const std::string& where) {
    if (!v) return fallback;
    const toml::array* a = v.as_array();
    if (!a) fail(file, where + ".dofs must be an array of DOF names (ux uy uz rx ry rz)");
    static const std::map<std::string, Dof> names = {{"ux", UX}, {"uy", UY}, {"uz", UZ}, {"rx", RX}, {"ry", RY}, {"rz", RZ}};
    DofMask m = 0;
    for (const auto& e : *a) {
        const auto s = e.value<std::string>();
        if (!s) fail(file, where + ".dofs holds a non-string");
        if (*s == "all") m |= kAllDofs;
        else if (auto it = names.find(*s); it != names.end()) m |= dof_bit(it->second);
        else fail(file, where + ".dofs: unknown DOF '" + *s + "' (ux uy uz rx ry rz all)");
    }
    return m;
}

template <class T>
T required(const toml::table& t, const char* key, const std::filesystem::path& file, const std::string& where) {
    const auto v = t[key].value<T>();
    if (!v) fail(file, where + " needs '" + key + "'" + (t.contains(key) ? " of the right type" : ""));
    return *v;
}

}  // namespace

ModalCase read_modal_case(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) throw InputError("case file '" + path.string() + "' does not exist");
    toml::table root;
    try {
        root = toml::parse_file(path.string());
    } catch (const toml::parse_error& e) {
        std::ostringstream msg;
        msg << "line " << e.source().begin.line << ": " << e.description();
        fail(path, msg.str());
    }
    const auto base = path.parent_path();
    ModalCase c;
    c.mesh = base / required<std::string>(root, "mesh", path, "the case");
    c.output = base / root["output"].value_or(path.stem().string() + "_modes");
    c.options.modes = static_cast<int>(root["modes"].value_or<int64_t>(10));
    c.options.shift_hz = root["shift_hz"].value_or(0.0);
    const std::string mass = root["mass"].value_or<std::string>("consistent");
    if (mass == "lumped") c.mass = solid::MassKind::Lumped;
    else if (mass != "consistent") fail(path, "mass = '" + mass + "' (consistent or lumped)");

    std::map<std::string, ElasticMaterial> materials;
    if (const toml::table* mats = root["materials"].as_table())
        for (const auto& [key, node] : *mats) {
            const std::string name(key.str());
            const toml::table* t = node.as_table();
            if (!t) fail(path, "materials." + name + " must be a table with E, nu, rho");
            const std::string where = "materials." + name;
            materials.emplace(name, ElasticMaterial::make(name, required<double>(*t, "E", path, where),
                                                          required<double>(*t, "nu", path, where),
                                                          required<double>(*t, "rho", path, where)));
        }
    const toml::array* parts = root["parts"].as_array();
    if (!parts || parts->empty()) fail(path, "no [[parts]]: give each part of the mesh a material");
    for (std::size_t i = 0; i < parts->size(); ++i) {
        const toml::table* t = (*parts)[i].as_table();
        const std::string where = fmt::format("parts[{}]", i);
        if (!t) fail(path, where + " must be a table");
        CasePart p;
        p.name = required<std::string>(*t, "name", path, where);
        const std::string mat = required<std::string>(*t, "material", path, where);
        auto it = materials.find(mat);
        if (it == materials.end()) fail(path, where + " (" + p.name + "): material '" + mat + "' is not defined under [materials]");
        p.material = it->second;
        p.thickness = (*t)["thickness"].value_or(0.0);
        if ((*t).contains("thickness") && !(p.thickness > 0))
            fail(path, where + " (" + p.name + "): thickness must be positive");
        c.parts.push_back(p);
    }
    if (const toml::array* sup = root["supports"].as_array())
        for (std::size_t i = 0; i < sup->size(); ++i) {
            const toml::table* t = (*sup)[i].as_table();
            const std::string where = fmt::format("supports[{}]", i);
            if (!t) fail(path, where + " must be a table");
            c.supports.push_back({required<std::string>(*t, "set", path, where), parse_dofs((*t)["dofs"], kAllDofs, path, where)});
        }
    if (const toml::array* cps = root["couplings"].as_array())
        for (std::size_t i = 0; i < cps->size(); ++i) {
            const toml::table* t = (*cps)[i].as_table();
            const std::string where = fmt::format("couplings[{}]", i);
            if (!t) fail(path, where + " must be a table");
            CaseCoupling cp;
            if (const toml::array* sets = (*t)["sets"].as_array()) {
                for (const auto& s : *sets)
                    if (auto v = s.value<std::string>()) cp.sets.push_back(*v);
                if (cp.sets.size() != 2) fail(path, where + ".sets must name two node sets (coincident node pairs)");
            } else {
                cp.sets.push_back(required<std::string>(*t, "set", path, where));
            }
            cp.dofs = parse_dofs((*t)["dofs"], kTranslations, path, where);
            c.couplings.push_back(cp);
        }
    return c;
}

std::string run_modal_case(const ModalCase& c) {
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
    const ModalResult r = solve_modes(sys, c.options);
    write_results(c.output, mesh, sys, r);
    return summary(sys, r) + "  results: " + c.output.string() + "/{frequencies.csv, modes.h5, modes.pvd}\n";
}

}  // namespace fem::modal
