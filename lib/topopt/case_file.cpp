#include "topopt/case_file.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "input/toml_input.hpp"
#include "material/elastic.hpp"
#include "mesh/gmsh.hpp"
#include "topopt/filter.hpp"

namespace fem::topopt {
namespace {

// Memory a topology optimization needs per element (mesh, model, stiffness pattern, Cholesky factor,
// filter weights), for refusing a grid that cannot fit before it is built. Measured peak resident
// size / elements of fem-topopt (2 iterations, filter radius about 3 elements): 4.9 and 3.9 kB for
// quad4 grids of 300 x 100 and 600 x 200, 16.6 and 15.0 kB for quad8 grids of 150 x 100 and 300 x 200.
constexpr double kBytesPerElement[] = {5e3, 17e3};  // quad4, quad8

// Nodes chosen by one of: edge, node_set, at, box.
std::vector<int> select_nodes(const input::TomlTable& t, const Mesh& mesh, double tol) {
    int given = 0;
    std::vector<int> ids;
    if (t.has("edge")) {
        ++given;
        const std::string edge = t.choice("edge", {"x0", "x1", "y0", "y1"});
        auto it = mesh.node_sets.find(edge);
        if (it == mesh.node_sets.end()) t.fail("edge", fmt::format("'{}' exists on rectangle domains only", edge));
        ids = it->second;
    }
    if (t.has("node_set")) {
        ++given;
        const std::string set = t.string("node_set");
        auto it = mesh.node_sets.find(set);
        if (it == mesh.node_sets.end()) {
            std::vector<std::string> known;
            for (const auto& [name, nodes] : mesh.node_sets) known.push_back(name);
            t.fail("node_set", fmt::format("node set '{}' is not in the mesh (known: {}){}", set, input::one_of(known),
                                           input::did_you_mean(set, known)));
        }
        ids = it->second;
    }
    if (t.has("at")) {
        ++given;
        const auto p = t.reals("at", 2);
        const Vec3 x(p[0], p[1], 0);
        const int n = nearest_node(mesh, x);
        const double d = (mesh.nodes[n] - x).norm();
        if (d > tol)
            t.fail("at", fmt::format("no node at ({}, {}): the nearest, node {}, is {:.3g} m away", p[0], p[1], n, d));
        ids = {n};
    }
    if (t.has("box")) {
        ++given;
        const auto b = t.reals("box", 4);
        if (!(b[0] <= b[2] && b[1] <= b[3])) t.fail("box", "must be [xmin, ymin, xmax, ymax] with xmin <= xmax and ymin <= ymax");
        ids = mesh.select_nodes([&](const Vec3& p) {
            return p.x() >= b[0] - tol && p.x() <= b[2] + tol && p.y() >= b[1] - tol && p.y() <= b[3] + tol;
        });
    }
    if (given != 1) t.fail("give exactly one of edge, node_set, at, box");
    if (ids.empty()) t.fail("the selection holds no node");
    return ids;
}

}  // namespace

Case parse_case(std::string_view text, const std::string& source, const std::filesystem::path& base) {
    const input::TomlDocument doc = input::TomlDocument::parse(text, source, base);
    const input::TomlTable root = doc.root();
    root.allow({"domain", "material", "optimization", "support", "load", "passive", "output"});
    Case c;
    std::ostringstream summary;

    // --- domain ---
    const auto dom = root.table("domain");
    dom.allow({"type", "size", "elements", "element", "mesh", "thickness"});
    const std::string type = dom.choice_or("type", {"rectangle", "gmsh"}, "rectangle");
    const double thickness = dom.real("thickness", input::Range::positive());
    if (type == "rectangle") {
        const auto size = dom.reals("size", 2, input::Range::positive());
        const auto n = dom.integers<int>("elements", 2, {.min = 1});
        const ElementShape shape = dom.choice_or("element", {"quad4", "quad8"}, "quad4") == "quad8" ? ElementShape::Quad8
                                                                                               : ElementShape::Quad4;
        const double elements = static_cast<double>(n[0]) * n[1];
        require_memory(elements * kBytesPerElement[shape == ElementShape::Quad8],
                       fmt::format("{}: a {} x {} {} design domain", dom.where("elements").str(), n[0], n[1], to_string(shape)));
        c.mesh = rectangle_quads(size[0], size[1], n[0], n[1], shape, "domain");
        summary << fmt::format("domain: {} x {} m, {} x {} {}", size[0], size[1], n[0], n[1], to_string(shape));
    } else {
        const std::filesystem::path p = dom.path("mesh");
        Mesh all = read_gmsh(p);
        // Keep the 2D quadrilateral blocks: the design domain (Gmsh may add line or point blocks).
        Mesh quads;
        quads.nodes = all.nodes;
        quads.node_sets = all.node_sets;
        for (auto& b : all.blocks)
            if (b.shape == ElementShape::Quad4 || b.shape == ElementShape::Quad8) quads.blocks.push_back(b);
        if (quads.blocks.empty()) dom.fail("mesh", fmt::format("{} holds no quad4 or quad8 elements", p.string()));
        std::vector<char> keep(quads.element_count(), 1);
        c.mesh = crop_by_flags(quads, keep);  // drops nodes that only lines or points used
        summary << fmt::format("domain: {} ({} elements)", p.string(), c.mesh.element_count());
    }

    // --- material ---
    const auto mat = root.table("material");
    mat.allow({"E", "nu", "name"});
    const auto material = ElasticMaterial::make(mat.string_or("name", "material"), mat.real("E", input::Range::positive()),
                                                mat.real("nu", input::Range::open(-1.0, 0.5)), 1.0);
    c.model = plane_stress_model(c.mesh, material, thickness);
    summary << fmt::format(", {} nodes, {} elements, E = {:g} Pa, nu = {:g}, t = {:g} m", c.mesh.node_count(),
                           c.model.element_count(), material.youngs_modulus, material.poissons_ratio, thickness);

    // Coordinate tolerance for node selections: 1e-6 of the domain's size.
    Vec3 lo = c.mesh.nodes.front(), hi = lo;
    for (const auto& p : c.mesh.nodes) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double tol = 1e-6 * (hi - lo).norm();

    // --- supports ---
    const auto supports = root.tables("support");
    if (supports.empty()) root.fail("no [[support]]: the domain must be held somewhere");
    for (const auto& t : supports) {
        t.allow({"edge", "node_set", "at", "box", "fix"});
        const auto nodes = select_nodes(t, c.mesh, tol);
        const auto fix = t.choices("fix", {"x", "y"});
        if (fix.empty()) t.fail("fix", "must list \"x\" and/or \"y\"");
        for (const auto& f : fix)
            for (int n : nodes) c.model.fix(n, f == "x" ? 0 : 1);
    }

    // --- loads ---
    const auto loads = root.tables("load");
    if (loads.empty()) root.fail("no [[load]]: nothing to optimize for");
    int cases = 0;
    for (const auto& t : loads) {
        t.allow({"edge", "node_set", "at", "box", "force", "case"});
        const auto nodes = select_nodes(t, c.mesh, tol);
        const auto f = t.reals("force", 2);
        // Cases are numbered 1, 2, ... without gaps, so there are at most as many as [[load]] entries.
        const int k = t.integer_or<int>("case", 1, {.min = 1});
        if (k > static_cast<int>(loads.size()))
            t.fail("case", fmt::format("load case {} cannot exist: cases are numbered 1, 2, ... without gaps and there are "
                                       "{} [[load]] entries", k, loads.size()));
        if (f[0] == 0 && f[1] == 0) t.fail("force", "the force is zero");
        for (int n : nodes) c.model.add_force(k - 1, n, Vec3(f[0], f[1], 0));
        cases = std::max(cases, k);
    }
    for (int k = 0; k < cases; ++k)
        if (static_cast<int>(c.model.loads.size()) <= k || c.model.loads[k].cwiseAbs().maxCoeff() == 0)
            root.fail(fmt::format("load case {} has no load (cases must be numbered 1, 2, ... without gaps)", k + 1));

    // --- passive regions ---
    for (const auto& t : root.tables("passive")) {
        t.allow({"kind", "circle", "box"});
        const Region region = t.choice("kind", {"void", "solid"}) == "void" ? Region::Void : Region::Solid;
        int n = 0;
        if (t.has("circle") == t.has("box")) t.fail("give exactly one of circle, box");
        if (t.has("circle")) {
            const auto ci = t.reals("circle", 3);
            if (!(ci[2] > 0)) t.fail("circle", fmt::format("the radius (third value) must be > 0, got {}", ci[2]));
            n = c.model.mark(region, [&](const Vec3& p) { return std::hypot(p.x() - ci[0], p.y() - ci[1]) < ci[2]; });
        } else {
            const auto b = t.reals("box", 4);
            n = c.model.mark(region, [&](const Vec3& p) { return p.x() >= b[0] && p.x() <= b[2] && p.y() >= b[1] && p.y() <= b[3]; });
        }
        if (n == 0) t.fail("the region holds no element centroid");
    }

    // --- optimization ---
    const auto opt = root.table("optimization");
    opt.allow({"removed", "volume_fraction", "penalty", "min_stiffness", "min_density", "filter", "filter_radius",
               "move_limit", "change_tolerance", "max_iterations", "oc_tolerance", "solver", "solver_tolerance",
               "projection", "projection_beta_max"});
    auto& s = c.settings;
    if (opt.has("removed") == opt.has("volume_fraction"))
        opt.fail("give exactly one of removed (fraction removed) and volume_fraction (fraction kept)");
    if (opt.has("removed")) s.volume_fraction = 1 - opt.real("removed", input::Range::open(0, 1));
    else s.volume_fraction = opt.real("volume_fraction", input::Range::open(0, 1));
    s.penalty = opt.real_or("penalty", s.penalty, input::Range::at_least(1));
    s.min_stiffness = opt.real_or("min_stiffness", s.min_stiffness, input::Range::open(0, 1));
    const std::string filter = opt.choice_or("filter", {"none", "sensitivity", "density"}, "sensitivity");
    s.filter = filter == "none" ? FilterKind::None : filter == "density" ? FilterKind::Density : FilterKind::Sensitivity;
    if (s.filter != FilterKind::None) {  // with filter = "none" a radius has no effect (and is refused as such)
        s.filter_radius = opt.real("filter_radius", input::Range::positive());
        // A radius beyond the domain's size is a unit mistake (mm for m), and its filter would couple
        // every element with every other.
        const double across = (hi - lo).norm();
        if (s.filter_radius > across)
            opt.fail("filter_radius", fmt::format("{} m is larger than the design domain ({:.3g} m across); the radius is in "
                                                  "metres and normally spans 1.5 to 3 elements", s.filter_radius, across));
        require_memory(Filter::estimated_bytes(c.model.centroid, s.filter_radius),
                       fmt::format("{}: a filter of radius {:g} m over {} elements", opt.where("filter_radius").str(),
                                   s.filter_radius, c.model.element_count()));
    }
    // Issue 16: the 99-line code's lower density bound (E = x^p E0, x >= x_min) instead of E_min.
    if (opt.has("min_density")) {
        if (opt.has("min_stiffness")) opt.fail("min_density", "give min_stiffness (E_min/E0) or min_density (x_min), not both");
        s.min_density = opt.real("min_density", input::Range::open(0, 1));
        s.min_stiffness = 0.0;
    }
    s.oc_tolerance = opt.real_or("oc_tolerance", s.oc_tolerance, input::Range::positive());  // the 88-line code: 1e-3
    const std::string solver = opt.choice_or("solver", {"auto", "direct", "multigrid"}, "auto");
    s.solver = solver == "direct" ? SolverKind::Direct : solver == "multigrid" ? SolverKind::Multigrid : SolverKind::Automatic;
    s.solver_tolerance = opt.real_or("solver_tolerance", s.solver_tolerance, input::Range::positive());
    const std::string projection = opt.choice_or("projection", {"none", "heaviside"}, "none");
    s.projection = projection == "heaviside" ? Projection::Heaviside : Projection::None;
    s.projection_beta_max = opt.real_or("projection_beta_max", s.projection_beta_max, input::Range::at_least(1));
    s.move_limit = opt.real_or("move_limit", s.move_limit, input::Range::left_open(0, 1));
    s.change_tolerance = opt.real_or("change_tolerance", s.change_tolerance, input::Range::positive());
    s.max_iterations = opt.integer_or<int>("max_iterations", s.max_iterations, {.min = 1});
    try {
        s.validate();
    } catch (const InputError& e) {
        opt.fail(e.what());
    }
    summary << fmt::format("\nsupports: {}, load cases: {}, volume kept: {:g}, filter: {} r = {:g} m, {}, OC bisection "
                           "to {:g}, solver: {}", supports.size(), c.model.loads.size(), s.volume_fraction, filter,
                           s.filter_radius,
                           s.min_density > 0 ? fmt::format("x_min = {:g}", s.min_density) : fmt::format("E_min/E0 = {:g}", s.min_stiffness),
                           s.oc_tolerance, solver);

    if (const auto out = root.optional_table("output")) {
        out->allow({"directory"});
        c.output_directory = out->string_or("directory", "topopt-out");
    }
    doc.finish();
    c.summary = summary.str();
    return c;
}

Case read_case(const std::filesystem::path& path) {
    const std::string text = [&] {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("cannot open case file '{}'", path.string()));
        std::ifstream in(path);
        if (!in) throw InputError(fmt::format("cannot open case file '{}'", path.string()));
        std::stringstream t;
        t << in.rdbuf();
        return t.str();
    }();
    return parse_case(text, path.string(), path.parent_path().empty() ? "." : path.parent_path());
}

}  // namespace fem::topopt
