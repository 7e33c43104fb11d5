#pragma once
// Geometry of the steel portal frame of thesis Sec 2.4.2 (Fig 2-8, 2-9, Table 2-4), meshed with
// MITC4 shells on the plates' mid-surfaces. The thesis does not print the frame's dimensions: they
// are reconstructed in README.md (the element counts of Table 2-4 fix the mesh topology, three
// dimensions are calibrated). This file only turns a set of dimensions into meshes:
//
//   single part: the two columns and the beam as one folded plate strip (corner lines shared),
//                no brackets, no screws (the thesis's "perfectly combined single component");
//   assembled:   three separate plates (corner lines NOT shared), two L brackets inside the top
//                corners, 16 screws = 16 pairs (plate node, bracket node), 4 per bracket leg in a 2 x 2
//                pattern, each coupled by the study (ANSYS CP sets; which DOFs is the study's choice),
//                with Geometry::screw_patch more facing pairs around each.
//
// Axes: the frame stands in the x-z plane (x along the span, z up), the plates' width runs along y.
// Mid-surfaces: left column x = 0, right column x = span, beam z = height; columns clamped at z = 0.
// Element normals point out of the frame (left column -x, beam +z, right column +x).
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace portal {

using fem::Vec3;

struct Geometry {
    double span = 0;               // L: between the columns' mid-surfaces [m]
    double height = 0;             // H: base to the beam's mid-surface [m]
    double width = 0;              // W: plate width (out of the frame's plane) [m]
    double thickness = 0;          // t: plates [m]
    double bracket_thickness = 0;  // t_b: L brackets [m]
    int across = 16;               // elements across the width (Table 2-4 topology: 16)
    int bracket_leg = 21;          // elements along each bracket leg (Table 2-4 topology: 21)
    std::array<int, 2> screw_rows = {7, 14};  // screws: leg node rows, counted from the corner
    // Screw model: 0 couples the one facing node pair on the screw's axis (a pin); 1 also the 8
    // facing pairs around it, a (2h)^2 = 19 mm square patch standing for the area a screw head and
    // washer clamp (README "Missing screws": the search over screw models).
    int screw_patch = 0;
    int refine = 1;                // subdivides every element refine x refine (convergence runs)

    double element_size() const { return width / across; }
    int column_elements() const { return std::max(1, static_cast<int>(std::lround(height / element_size()))); }
    int beam_elements() const { return std::max(1, static_cast<int>(std::lround(span / element_size()))); }
};

/// One screw: the plate node and the bracket node on its axis, and every facing (plate, bracket) node
/// pair it couples (the axis pair first; more with Geometry::screw_patch).
struct Screw {
    std::string name;  // e.g. "L-col-1": left corner, column leg, screw 1 (see README.md)
    int plate_node = -1, bracket_node = -1;
    std::vector<std::pair<int, int>> pairs;
};

struct FrameMesh {
    fem::Mesh mesh;              // blocks: "column_left", "beam", "column_right"[, "bracket_left", "bracket_right"]
    std::vector<int> base;       // clamped nodes (z = 0)
    std::vector<Screw> screws;   // empty for the single-part model
};

namespace detail {

// Nodes along a path (points path[i]) times m + 1 nodes across (y from 0 to W); returns node[i][k].
inline std::vector<std::vector<int>> add_rows(fem::Mesh& mesh, const std::vector<Vec3>& path, int m, double W) {
    std::vector<std::vector<int>> id(path.size(), std::vector<int>(m + 1));
    for (std::size_t i = 0; i < path.size(); ++i)
        for (int k = 0; k <= m; ++k) id[i][k] = mesh.add_node(path[i] + Vec3(0, W * k / m, 0));
    return id;
}

// Quads between consecutive rows i, i+1 (r along the path, s across): normal = path direction x y.
inline void add_quads(fem::ElementBlock& b, const std::vector<std::vector<int>>& id, std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to; ++i)
        for (std::size_t k = 0; k + 1 < id[i].size(); ++k) {
            const int q[4] = {id[i][k], id[i + 1][k], id[i + 1][k + 1], id[i][k + 1]};
            b.add(q);
        }
}

// n + 1 equally spaced points from a to b (inclusive).
inline std::vector<Vec3> segment(const Vec3& a, const Vec3& b, int n) {
    std::vector<Vec3> p;
    for (int i = 0; i <= n; ++i) p.push_back(a + (b - a) * (static_cast<double>(i) / n));
    return p;
}

inline void check(const Geometry& g) {
    auto positive = [](double v, const char* what) {
        if (!(v > 0) || !std::isfinite(v)) throw fem::InputError(std::string("portal frame: ") + what + " must be positive");
    };
    positive(g.span, "span");
    positive(g.height, "height");
    positive(g.width, "width");
    positive(g.thickness, "thickness");
    positive(g.bracket_thickness, "bracket thickness");
    if (g.across < 2 || g.refine < 1 || g.bracket_leg < 2)
        throw fem::InputError("portal frame: needs at least 2 elements across and along a bracket leg");
    if (g.screw_patch < 0 || g.screw_patch * 4 >= g.across || g.screw_rows[0] <= g.screw_patch ||
        g.screw_rows[1] + g.screw_patch >= g.bracket_leg)
        throw fem::InputError("portal frame: the screw patch reaches past the bracket leg or the plate's edge");
    if (g.bracket_leg >= g.column_elements() || 2 * g.bracket_leg >= g.beam_elements())
        throw fem::InputError("portal frame: bracket legs longer than the column or half the beam");
}

}  // namespace detail

/// The single-part model: one folded strip, left column bottom -> corner -> beam -> corner -> right
/// column bottom, the corner node lines shared.
inline FrameMesh single_part(const Geometry& g) {
    detail::check(g);
    const int r = g.refine, m = g.across * r, nc = g.column_elements() * r, nb = g.beam_elements() * r;
    const double L = g.span, H = g.height;
    std::vector<Vec3> path = detail::segment(Vec3(0, 0, 0), Vec3(0, 0, H), nc);
    for (const Vec3& p : detail::segment(Vec3(0, 0, H), Vec3(L, 0, H), nb)) if (p.x() > 0) path.push_back(p);
    for (const Vec3& p : detail::segment(Vec3(L, 0, H), Vec3(L, 0, 0), nc)) if (p.z() < H) path.push_back(p);
    FrameMesh f;
    const auto id = detail::add_rows(f.mesh, path, m, g.width);
    fem::ElementBlock left{"column_left", fem::ElementShape::Quad4, {}}, beam{"beam", fem::ElementShape::Quad4, {}},
        right{"column_right", fem::ElementShape::Quad4, {}};
    detail::add_quads(left, id, 0, nc);
    detail::add_quads(beam, id, nc, nc + nb);
    detail::add_quads(right, id, nc + nb, 2 * nc + nb);
    f.mesh.blocks = {left, beam, right};
    for (int k = 0; k <= m; ++k) {
        f.base.push_back(id.front()[k]);
        f.base.push_back(id.back()[k]);
    }
    f.mesh.node_sets["base"] = f.base;
    return f;
}

/// The assembled model: three plates with their own corner nodes, two L brackets, 16 screws.
inline FrameMesh assembled(const Geometry& g) {
    detail::check(g);
    const int r = g.refine, m = g.across * r, nc = g.column_elements() * r, nb = g.beam_elements() * r;
    const int leg = g.bracket_leg * r;
    const double L = g.span, H = g.height, W = g.width;
    const double hc = H / nc, hb = L / nb;
    // Bracket mid-surface: against the inner faces of column and beam, offset (t + t_b)/2.
    const double d = 0.5 * (g.thickness + g.bracket_thickness);
    FrameMesh f;
    fem::Mesh& mesh = f.mesh;

    const auto col_l = detail::add_rows(mesh, detail::segment(Vec3(0, 0, 0), Vec3(0, 0, H), nc), m, W);
    const auto beam = detail::add_rows(mesh, detail::segment(Vec3(0, 0, H), Vec3(L, 0, H), nb), m, W);
    const auto col_r = detail::add_rows(mesh, detail::segment(Vec3(L, 0, H), Vec3(L, 0, 0), nc), m, W);

    // Bracket leg nodes sit at the same in-plane positions as the plate nodes they face (row j from
    // the corner at distance j h), so that a screw couples two nodes on one normal line; the corner
    // row is at the bracket's own corner (offset d).
    std::vector<Vec3> bl, br;
    for (int j = leg; j >= 1; --j) bl.emplace_back(d, 0, H - j * hc);
    bl.emplace_back(d, 0, H - d);
    for (int j = 1; j <= leg; ++j) bl.emplace_back(j * hb, 0, H - d);
    for (int j = leg; j >= 1; --j) br.emplace_back(L - j * hb, 0, H - d);
    br.emplace_back(L - d, 0, H - d);
    for (int j = 1; j <= leg; ++j) br.emplace_back(L - d, 0, H - j * hc);
    const auto brk_l = detail::add_rows(mesh, bl, m, W);
    const auto brk_r = detail::add_rows(mesh, br, m, W);

    auto block = [&](const char* part, const std::vector<std::vector<int>>& id) {
        fem::ElementBlock b{part, fem::ElementShape::Quad4, {}};
        detail::add_quads(b, id, 0, id.size() - 1);
        mesh.blocks.push_back(std::move(b));
    };
    block("column_left", col_l);
    block("beam", beam);
    block("column_right", col_r);
    block("bracket_left", brk_l);
    block("bracket_right", brk_r);

    for (int k = 0; k <= m; ++k) {
        f.base.push_back(col_l.front()[k]);
        f.base.push_back(col_r.back()[k]);
    }
    mesh.node_sets["base"] = f.base;

    // Screws: rows screw_rows (from the corner) x columns at 1/4 and 3/4 of the width.
    const int k1 = m / 4, k2 = 3 * m / 4;
    int count = 0;
    // The facing (plate, bracket) nodes at leg row j (from the corner) and width index k.
    auto facing = [&](const std::string& w, int j, int k) -> std::pair<int, int> {
        if (w == "L-col") return {col_l[nc - j][k], brk_l[leg - j][k]};
        if (w == "L-beam") return {beam[j][k], brk_l[leg + j][k]};
        if (w == "R-beam") return {beam[nb - j][k], brk_r[leg - j][k]};
        return {col_r[j][k], brk_r[leg + j][k]};  // R-col
    };
    const int p = g.screw_patch * r;
    for (const char* where : {"L-col", "L-beam", "R-beam", "R-col"}) {
        count = 0;
        const std::string w = where;
        for (int row : g.screw_rows)
            for (int k : {k1, k2}) {
                const int j = row * r;
                Screw s{w + "-" + std::to_string(++count), facing(w, j, k).first, facing(w, j, k).second, {}};
                s.pairs.push_back(facing(w, j, k));
                for (int dj = -p; dj <= p; ++dj)
                    for (int dk = -p; dk <= p; ++dk)
                        if (dj != 0 || dk != 0) s.pairs.push_back(facing(w, j + dj, k + dk));
                f.screws.push_back(std::move(s));
            }
    }
    return f;
}

}  // namespace portal
