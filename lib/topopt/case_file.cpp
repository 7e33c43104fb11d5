#include "topopt/case_file.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/error.hpp"
#include "material/elastic.hpp"
#include "mesh/gmsh.hpp"

namespace fem::topopt {
namespace {

struct Reader {
    std::string source;

    [[noreturn]] void fail(const toml::node& where, const std::string& what) const {
        throw InputError(fmt::format("{}:{}: {}", source, where.source().begin.line, what));
    }
    [[noreturn]] void fail(const std::string& what) const { throw InputError(fmt::format("{}: {}", source, what)); }

    // Refuses keys the program does not know (a misspelt key must not be silently ignored).
    void only(const toml::table& t, const std::string& table, std::set<std::string> keys) const {
        for (const auto& [k, v] : t)
            if (!keys.count(std::string(k.str())))
                fail(v, fmt::format("[{}]: unknown key '{}'", table, k.str()));
    }
    const toml::table& table(const toml::table& root, const char* name) const {
        const auto* t = root[name].as_table();
        if (!t) fail(fmt::format("missing table [{}]", name));
        return *t;
    }
    double number(const toml::table& t, const std::string& table, const char* key) const {
        auto v = t[key].value<double>();
        if (!v) fail(t, fmt::format("[{}]: '{}' must be a number", table, key));
        return *v;
    }
    std::vector<double> numbers(const toml::table& t, const std::string& table, const char* key, std::size_t n) const {
        const auto* a = t[key].as_array();
        if (!a || a->size() != n) fail(t, fmt::format("[{}]: '{}' must be an array of {} numbers", table, key, n));
        std::vector<double> out;
        for (const auto& x : *a) {
            auto v = x.value<double>();
            if (!v) fail(t, fmt::format("[{}]: '{}' must hold numbers", table, key));
            out.push_back(*v);
        }
        return out;
    }
};

// Nodes chosen by one of: edge, node_set, at, box.
std::vector<int> select_nodes(const Reader& r, const toml::table& t, const std::string& what, const Mesh& mesh,
                              double tol) {
    int given = 0;
    std::vector<int> ids;
    if (auto edge = t["edge"].value<std::string>()) {
        ++given;
        if (*edge != "x0" && *edge != "x1" && *edge != "y0" && *edge != "y1")
            r.fail(t, fmt::format("{}: edge '{}' is not one of x0, x1, y0, y1", what, *edge));
        auto it = mesh.node_sets.find(*edge);
        if (it == mesh.node_sets.end()) r.fail(t, fmt::format("{}: edge '{}' exists on rectangle domains only", what, *edge));
        ids = it->second;
    }
    if (auto set = t["node_set"].value<std::string>()) {
        ++given;
        auto it = mesh.node_sets.find(*set);
        if (it == mesh.node_sets.end()) {
            std::string known;
            for (const auto& [name, nodes] : mesh.node_sets) known += (known.empty() ? "" : ", ") + name;
            r.fail(t, fmt::format("{}: node set '{}' is not in the mesh (known: {})", what, *set, known));
        }
        ids = it->second;
    }
    if (t.contains("at")) {
        ++given;
        const auto p = r.numbers(t, what, "at", 2);
        const Vec3 x(p[0], p[1], 0);
        const int n = nearest_node(mesh, x);
        const double d = (mesh.nodes[n] - x).norm();
        if (d > tol)
            r.fail(t, fmt::format("{}: no node at ({}, {}): the nearest, node {}, is {:.3g} m away", what, p[0], p[1], n, d));
        ids = {n};
    }
    if (t.contains("box")) {
        ++given;
        const auto b = r.numbers(t, what, "box", 4);
        ids = mesh.select_nodes([&](const Vec3& p) {
            return p.x() >= b[0] - tol && p.x() <= b[2] + tol && p.y() >= b[1] - tol && p.y() <= b[3] + tol;
        });
    }
    if (given != 1) r.fail(t, fmt::format("{}: give exactly one of edge, node_set, at, box", what));
    if (ids.empty()) r.fail(t, fmt::format("{}: the selection holds no node", what));
    return ids;
}

}  // namespace

Case parse_case(std::string_view text, const std::string& source, const std::filesystem::path& base) {
    Reader r{source};
    toml::table root;
    try {
        root = toml::parse(text, source);
    } catch (const toml::parse_error& e) {
        throw InputError(fmt::format("{}:{}: {}", source, e.source().begin.line, e.description()));
    }
    r.only(root, "case file", {"domain", "material", "optimization", "support", "load", "passive", "output"});
    Case c;
    std::ostringstream summary;

    // --- domain ---
    const auto& dom = r.table(root, "domain");
    r.only(dom, "domain", {"type", "size", "elements", "element", "mesh", "thickness"});
    const std::string type = dom["type"].value<std::string>().value_or("rectangle");
    const double thickness = r.number(dom, "domain", "thickness");
    if (!(thickness > 0)) r.fail(dom, fmt::format("[domain]: thickness must be > 0, got {}", thickness));
    if (type == "rectangle") {
        const auto size = r.numbers(dom, "domain", "size", 2);
        const auto n = r.numbers(dom, "domain", "elements", 2);
        if (!(size[0] > 0 && size[1] > 0)) r.fail(dom, "[domain]: size must be positive");
        if (n[0] < 1 || n[1] < 1 || n[0] != std::floor(n[0]) || n[1] != std::floor(n[1]))
            r.fail(dom, "[domain]: elements must be two positive integers");
        const ElementShape shape = element_shape_from_string(dom["element"].value<std::string>().value_or("quad4"));
        c.mesh = rectangle_quads(size[0], size[1], static_cast<int>(n[0]), static_cast<int>(n[1]), shape, "domain");
        summary << fmt::format("domain: {} x {} m, {} x {} {}", size[0], size[1], n[0], n[1], to_string(shape));
    } else if (type == "gmsh") {
        auto mesh = dom["mesh"].value<std::string>();
        if (!mesh) r.fail(dom, "[domain]: type = \"gmsh\" needs mesh = \"file.msh\"");
        const std::filesystem::path p = std::filesystem::path(*mesh).is_absolute() ? std::filesystem::path(*mesh) : base / *mesh;
        Mesh all = read_gmsh(p);
        // Keep the 2D quadrilateral blocks: the design domain (Gmsh may add line or point blocks).
        Mesh quads;
        quads.nodes = all.nodes;
        quads.node_sets = all.node_sets;
        for (auto& b : all.blocks)
            if (b.shape == ElementShape::Quad4 || b.shape == ElementShape::Quad8) quads.blocks.push_back(b);
        if (quads.blocks.empty()) r.fail(dom, fmt::format("[domain]: {} holds no quad4 or quad8 elements", p.string()));
        std::vector<char> keep(quads.element_count(), 1);
        c.mesh = crop_by_flags(quads, keep);  // drops nodes that only lines or points used
        summary << fmt::format("domain: {} ({} elements)", p.string(), c.mesh.element_count());
    } else {
        r.fail(dom, fmt::format("[domain]: type '{}' is not rectangle or gmsh", type));
    }

    // --- material ---
    const auto& mat = r.table(root, "material");
    r.only(mat, "material", {"E", "nu", "name"});
    const auto material = ElasticMaterial::make(mat["name"].value<std::string>().value_or("material"),
                                                r.number(mat, "material", "E"), r.number(mat, "material", "nu"), 1.0);
    c.model = plane_stress_model(c.mesh, material, thickness);
    summary << fmt::format(", {} nodes, {} elements, E = {:g} Pa, nu = {:g}, t = {:g} m", c.mesh.node_count(),
                           c.model.element_count(), material.youngs_modulus, material.poissons_ratio, thickness);

    // Coordinate tolerance for node selections: 1e-6 of the domain's size.
    Vec3 lo = c.mesh.nodes.front(), hi = lo;
    for (const auto& p : c.mesh.nodes) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double tol = 1e-6 * (hi - lo).norm();

    // --- supports ---
    const auto* supports = root["support"].as_array();
    if (!supports || supports->empty()) r.fail("no [[support]]: the domain must be held somewhere");
    for (std::size_t i = 0; i < supports->size(); ++i) {
        const auto* t = (*supports)[i].as_table();
        const std::string what = fmt::format("support {}", i + 1);
        if (!t) r.fail(what + " is not a table");
        r.only(*t, what, {"edge", "node_set", "at", "box", "fix"});
        const auto nodes = select_nodes(r, *t, what, c.mesh, tol);
        const auto* fix = (*t)["fix"].as_array();
        if (!fix || fix->empty()) r.fail(*t, what + ": 'fix' must list \"x\" and/or \"y\"");
        for (const auto& f : *fix) {
            const auto s = f.value<std::string>().value_or("");
            if (s != "x" && s != "y") r.fail(*t, fmt::format("{}: cannot fix '{}' (x or y)", what, s));
            for (int n : nodes) c.model.fix(n, s == "x" ? 0 : 1);
        }
    }

    // --- loads ---
    const auto* loads = root["load"].as_array();
    if (!loads || loads->empty()) r.fail("no [[load]]: nothing to optimize for");
    int cases = 0;
    for (std::size_t i = 0; i < loads->size(); ++i) {
        const auto* t = (*loads)[i].as_table();
        const std::string what = fmt::format("load {}", i + 1);
        if (!t) r.fail(what + " is not a table");
        r.only(*t, what, {"edge", "node_set", "at", "box", "force", "case"});
        const auto nodes = select_nodes(r, *t, what, c.mesh, tol);
        const auto f = r.numbers(*t, what, "force", 2);
        const double k = (*t)["case"].value<double>().value_or(1.0);
        if (k < 1 || k != std::floor(k)) r.fail(*t, fmt::format("{}: case must be an integer >= 1", what));
        if (f[0] == 0 && f[1] == 0) r.fail(*t, what + ": the force is zero");
        for (int n : nodes) c.model.add_force(static_cast<int>(k) - 1, n, Vec3(f[0], f[1], 0));
        cases = std::max(cases, static_cast<int>(k));
    }
    for (int k = 0; k < cases; ++k)
        if (static_cast<int>(c.model.loads.size()) <= k || c.model.loads[k].cwiseAbs().maxCoeff() == 0)
            r.fail(fmt::format("load case {} has no load (cases must be numbered 1, 2, ... without gaps)", k + 1));

    // --- passive regions ---
    if (const auto* passive = root["passive"].as_array()) {
        for (std::size_t i = 0; i < passive->size(); ++i) {
            const auto* t = (*passive)[i].as_table();
            const std::string what = fmt::format("passive {}", i + 1);
            if (!t) r.fail(what + " is not a table");
            r.only(*t, what, {"kind", "circle", "box"});
            const std::string kind = (*t)["kind"].value<std::string>().value_or("");
            if (kind != "void" && kind != "solid") r.fail(*t, fmt::format("{}: kind must be \"void\" or \"solid\"", what));
            const Region region = kind == "void" ? Region::Void : Region::Solid;
            int n = 0;
            if (t->contains("circle") == t->contains("box")) r.fail(*t, what + ": give exactly one of circle, box");
            if (t->contains("circle")) {
                const auto ci = r.numbers(*t, what, "circle", 3);
                n = c.model.mark(region, [&](const Vec3& p) { return std::hypot(p.x() - ci[0], p.y() - ci[1]) < ci[2]; });
            } else {
                const auto b = r.numbers(*t, what, "box", 4);
                n = c.model.mark(region, [&](const Vec3& p) { return p.x() >= b[0] && p.x() <= b[2] && p.y() >= b[1] && p.y() <= b[3]; });
            }
            if (n == 0) r.fail(*t, what + ": the region holds no element centroid");
        }
    }

    // --- optimization ---
    const auto& opt = r.table(root, "optimization");
    r.only(opt, "optimization", {"removed", "volume_fraction", "penalty", "min_stiffness", "min_density", "filter",
                                 "filter_radius", "move_limit", "change_tolerance", "max_iterations", "oc_tolerance",
                                 "solver", "solver_tolerance", "projection", "projection_beta_max"});
    auto& s = c.settings;
    if (opt.contains("removed") == opt.contains("volume_fraction"))
        r.fail(opt, "[optimization]: give exactly one of removed (fraction removed) and volume_fraction (fraction kept)");
    if (opt.contains("removed")) {
        const double removed = r.number(opt, "optimization", "removed");
        if (!(removed > 0 && removed < 1)) r.fail(opt, fmt::format("[optimization]: removed must lie in (0, 1), got {}", removed));
        s.volume_fraction = 1 - removed;
    } else {
        s.volume_fraction = r.number(opt, "optimization", "volume_fraction");
        if (!(s.volume_fraction > 0 && s.volume_fraction < 1))
            r.fail(opt, fmt::format("[optimization]: volume_fraction must lie in (0, 1), got {}", s.volume_fraction));
    }
    s.penalty = opt["penalty"].value<double>().value_or(s.penalty);
    s.min_stiffness = opt["min_stiffness"].value<double>().value_or(s.min_stiffness);
    // Issue 16: the 99-line code's lower density bound (E = x^p E0, x >= x_min) instead of E_min.
    if (opt.contains("min_density")) {
        if (opt.contains("min_stiffness")) r.fail(opt, "[optimization]: give min_stiffness (E_min/E0) or min_density (x_min), not both");
        s.min_density = r.number(opt, "optimization", "min_density");
        s.min_stiffness = 0.0;
    }
    s.oc_tolerance = opt["oc_tolerance"].value<double>().value_or(s.oc_tolerance);  // the 88-line code: 1e-3
    const std::string solver = opt["solver"].value<std::string>().value_or("auto");
    if (solver == "auto") s.solver = SolverKind::Automatic;
    else if (solver == "direct") s.solver = SolverKind::Direct;
    else if (solver == "multigrid") s.solver = SolverKind::Multigrid;
    else r.fail(opt, fmt::format("[optimization]: solver '{}' is not auto, direct or multigrid", solver));
    s.solver_tolerance = opt["solver_tolerance"].value<double>().value_or(s.solver_tolerance);
    const std::string projection = opt["projection"].value<std::string>().value_or("none");
    if (projection == "none") s.projection = Projection::None;
    else if (projection == "heaviside") s.projection = Projection::Heaviside;
    else r.fail(opt, fmt::format("[optimization]: projection '{}' is not none or heaviside", projection));
    s.projection_beta_max = opt["projection_beta_max"].value<double>().value_or(s.projection_beta_max);
    const std::string filter = opt["filter"].value<std::string>().value_or("sensitivity");
    if (filter == "none") s.filter = FilterKind::None;
    else if (filter == "sensitivity") s.filter = FilterKind::Sensitivity;
    else if (filter == "density") s.filter = FilterKind::Density;
    else r.fail(opt, fmt::format("[optimization]: filter '{}' is not none, sensitivity or density", filter));
    s.filter_radius = opt["filter_radius"].value<double>().value_or(0.0);
    s.move_limit = opt["move_limit"].value<double>().value_or(s.move_limit);
    s.change_tolerance = opt["change_tolerance"].value<double>().value_or(s.change_tolerance);
    s.max_iterations = static_cast<int>(opt["max_iterations"].value<double>().value_or(s.max_iterations));
    try {
        s.validate();
    } catch (const InputError& e) {
        r.fail(opt, std::string("[optimization]: ") + e.what());
    }
    summary << fmt::format("\nsupports: {}, load cases: {}, volume kept: {:g}, filter: {} r = {:g} m, {}, OC bisection "
                           "to {:g}, solver: {}", supports->size(), c.model.loads.size(), s.volume_fraction, filter,
                           s.filter_radius,
                           s.min_density > 0 ? fmt::format("x_min = {:g}", s.min_density) : fmt::format("E_min/E0 = {:g}", s.min_stiffness),
                           s.oc_tolerance, solver);

    if (const auto* out = root["output"].as_table()) {
        r.only(*out, "output", {"directory"});
        c.output_directory = (*out)["directory"].value<std::string>().value_or("topopt-out");
    }
    c.summary = summary.str();
    return c;
}

Case read_case(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError(fmt::format("cannot open case file '{}'", path.string()));
    std::stringstream text;
    text << in.rdbuf();
    return parse_case(text.str(), path.string(), path.parent_path().empty() ? "." : path.parent_path());
}

}  // namespace fem::topopt
