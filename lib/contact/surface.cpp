#include "contact/surface.hpp"

#include <algorithm>
#include <set>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::contact {

namespace {

constexpr double kGauss = 0.57735026918962576;  // 1 / sqrt(3)

// Face corner lists (local node numbers) of the solids; orientation is fixed geometrically below,
// so the lists only need to go round each face.
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

// Tet10 mid-edge node of corner edge (a, b) in Gmsh order: 01 -> 4, 12 -> 5, 20 -> 6, 03 -> 7,
// 23 -> 8, 13 -> 9 (mesh/element_shape.hpp).
int tet10_mid_node(int a, int b) {
    if (a > b) std::swap(a, b);
    if (a == 0) return b == 1 ? 4 : (b == 2 ? 6 : 7);
    if (a == 1) return b == 2 ? 5 : 9;
    return 8;  // (2, 3)
}

Vec3 face_normal(const Segment& s, std::span<const Vec3> x) {
    if (s.count == 3) return (x[s.n[1]] - x[s.n[0]]).cross(x[s.n[2]] - x[s.n[0]]);
    return (x[s.n[2]] - x[s.n[0]]).cross(x[s.n[3]] - x[s.n[1]]);
}

}  // namespace

double segment_area(const Segment& s, std::span<const Vec3> x) {
    if (s.count == 3) return 0.5 * face_normal(s, x).norm();
    const Vec3 &a = x[s.n[0]], &b = x[s.n[1]], &c = x[s.n[2]], &d = x[s.n[3]];
    double A = 0.0;
    for (double xi : {-kGauss, kGauss})
        for (double eta : {-kGauss, kGauss}) {
            const Vec3 dxi = 0.25 * ((1 - eta) * (b - a) + (1 + eta) * (c - d));
            const Vec3 deta = 0.25 * ((1 - xi) * (d - a) + (1 + xi) * (c - b));
            A += dxi.cross(deta).norm();  // weights 1, |J| of the bilinear map
        }
    return A;
}

double element_volume(ElementShape shape, std::span<const Vec3> x) {
    if (shape == ElementShape::Tet4 || shape == ElementShape::Tet10)
        return std::abs((x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0]))) / 6.0;
    if (shape != ElementShape::Hex8) throw InputError(fmt::format("element_volume: {} is not a solid", to_string(shape)));
    static constexpr double s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                       {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    double V = 0.0;
    for (double g0 : {-kGauss, kGauss})
        for (double g1 : {-kGauss, kGauss})
            for (double g2 : {-kGauss, kGauss}) {
                Mat3 J = Mat3::Zero();  // columns: dx/dxi, dx/deta, dx/dzeta
                for (int i = 0; i < 8; ++i) {
                    const double a = 1 + s[i][0] * g0, b = 1 + s[i][1] * g1, c = 1 + s[i][2] * g2;
                    J.col(0) += 0.125 * s[i][0] * b * c * x[i];
                    J.col(1) += 0.125 * s[i][1] * a * c * x[i];
                    J.col(2) += 0.125 * s[i][2] * a * b * x[i];
                }
                V += J.determinant();
            }
    return std::abs(V);
}

ContactSurface ContactSurface::from_part(const Mesh& mesh, std::string_view part, const ElasticMaterial& material,
                                         double sf, double shell_thickness) {
    if (!(sf > 0.0)) throw InputError(fmt::format("contact surface of part '{}': scale factor {} must be > 0", part, sf));
    if (!(shell_thickness >= 0.0) || !std::isfinite(shell_thickness))
        throw InputError(fmt::format("contact surface of part '{}': shell thickness {} must be >= 0", part,
                                     shell_thickness));
    ContactSurface surf;
    surf.name = std::string(part);
    const double B = bulk_modulus(material);
    std::span<const Vec3> X(mesh.nodes);

    // Faces keyed by their sorted corner nodes; a face met twice is interior.
    struct Face {
        Segment seg;
        int uses = 0;
        std::array<int, 3> mid{-1, -1, -1};  // tet10: mid-edge nodes of the face (slave nodes too)
    };
    std::map<std::array<int, 4>, Face> faces;
    auto key_of = [](const Segment& s) {
        std::array<int, 4> k{s.n[0], s.n[1], s.n[2], s.count == 4 ? s.n[3] : std::numeric_limits<int>::max()};
        std::sort(k.begin(), k.end());  // a triangle's unused slot sorts last
        return k;
    };
    for (int b : mesh.blocks_of_part(part)) {
        const ElementBlock& blk = mesh.blocks[b];
        const bool hex = blk.shape == ElementShape::Hex8;
        const bool tet = blk.shape == ElementShape::Tet4 || blk.shape == ElementShape::Tet10;
        const bool shell = blk.shape == ElementShape::Quad4 || blk.shape == ElementShape::Tri3;
        if (!hex && !tet && !shell) continue;  // beams, point masses: no surface
        for (int e = 0; e < blk.size(); ++e) {
            const auto conn = blk.element(e);
            if (shell) {
                Segment s;
                s.count = blk.shape == ElementShape::Quad4 ? 4 : 3;
                for (int i = 0; i < s.count; ++i) s.n[i] = conn[i];
                s.block = b;
                s.element = e;
                s.area = segment_area(s, X);
                double diag = s.count == 4 ? std::max((X[s.n[2]] - X[s.n[0]]).norm(), (X[s.n[3]] - X[s.n[1]]).norm())
                                           : std::max({(X[s.n[1]] - X[s.n[0]]).norm(), (X[s.n[2]] - X[s.n[1]]).norm(),
                                                       (X[s.n[0]] - X[s.n[2]]).norm()});
                s.stiffness = shell_penalty_stiffness(B, s.area, diag, sf);  // Eq 2-30b
                s.depth = 0.5 * diag;
                s.offset = 0.5 * shell_thickness;
                s.two_sided = shell_thickness > 0.0;
                surf.segments.push_back(s);
                continue;
            }
            const int corners = hex ? 8 : 4;
            std::vector<Vec3> xc(corners);
            Vec3 centre = Vec3::Zero();
            for (int i = 0; i < corners; ++i) {
                xc[i] = X[conn[i]];
                centre += xc[i] / corners;
            }
            const double V = element_volume(blk.shape, xc);
            const int nf = hex ? 6 : 4;
            for (int f = 0; f < nf; ++f) {
                Segment s;
                s.count = hex ? 4 : 3;
                for (int i = 0; i < s.count; ++i) s.n[i] = conn[hex ? kHexFaces[f][i] : kTetFaces[f][i]];
                Vec3 fc = Vec3::Zero();
                for (int i = 0; i < s.count; ++i) fc += X[s.n[i]] / s.count;
                if (face_normal(s, X).dot(fc - centre) < 0) std::swap(s.n[1], s.n[s.count - 1]);  // reverse: outward
                s.block = b;
                s.element = e;
                s.volume = V;
                s.area = segment_area(s, X);
                s.stiffness = solid_penalty_stiffness(B, s.area, V, sf);  // Eq 2-30a
                s.depth = 0.5 * V / s.area;
                Face& face = faces[key_of(s)];
                if (face.uses++ == 0) {
                    face.seg = s;
                    if (blk.shape == ElementShape::Tet10)
                        for (int i = 0; i < 3; ++i) face.mid[i] = conn[tet10_mid_node(kTetFaces[f][i], kTetFaces[f][(i + 1) % 3])];
                }
            }
        }
    }
    std::map<int, std::pair<double, double>> k_node;  // node -> (smallest k, smallest element size)
    auto add_node = [&](int node, const Segment& s) {
        const double size = s.volume > 0.0 ? s.volume / s.area : std::sqrt(s.area);
        auto [it, fresh] = k_node.emplace(node, std::pair{s.stiffness, size});
        if (!fresh) it->second = {std::min(it->second.first, s.stiffness), std::min(it->second.second, size)};
    };
    for (const auto& [k, f] : faces)
        if (f.uses == 1) {
            surf.segments.push_back(f.seg);
            for (int m : f.mid)
                if (m >= 0) add_node(m, f.seg);
        }
    if (surf.segments.empty())
        throw InputError(fmt::format("contact surface of part '{}': the part has no solid or shell elements", part));
    // Deterministic order: by owning block and element.
    std::stable_sort(surf.segments.begin(), surf.segments.end(), [](const Segment& a, const Segment& b) {
        return a.block != b.block ? a.block < b.block : a.element < b.element;
    });
    for (const auto& s : surf.segments)
        for (int i = 0; i < s.count; ++i) add_node(s.n[i], s);
    std::map<int, double> offset;  // slave nodes of shells carry half the thickness
    for (const auto& s : surf.segments)
        for (int i = 0; i < s.count; ++i) offset[s.n[i]] = std::max(offset[s.n[i]], s.offset);
    for (const auto& [node, k] : k_node) {
        surf.nodes.push_back(node);
        surf.node_stiffness.push_back(k.first);
        surf.node_size.push_back(k.second);
        surf.node_offset.push_back(offset[node]);
    }
    return surf;
}

ContactSurface ContactSurface::merge(std::string name, const std::vector<ContactSurface>& parts) {
    ContactSurface m;
    m.name = std::move(name);
    struct NodeData { int node; double stiffness, size, offset; };
    std::vector<NodeData> nodes;
    for (const auto& p : parts) {
        if (p.rigid) throw InputError(fmt::format("contact surface '{}': cannot merge rigid surface '{}'", m.name, p.name));
        m.segments.insert(m.segments.end(), p.segments.begin(), p.segments.end());
        for (std::size_t i = 0; i < p.nodes.size(); ++i)
            nodes.push_back({p.nodes[i], p.node_stiffness[i], p.node_size[i], p.node_offset[i]});
    }
    std::sort(nodes.begin(), nodes.end(), [](const NodeData& a, const NodeData& b) { return a.node < b.node; });
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (i > 0 && nodes[i].node == nodes[i - 1].node)
            throw InputError(fmt::format("contact surface '{}': node {} belongs to two of the merged parts", m.name,
                                         nodes[i].node));
        m.nodes.push_back(nodes[i].node);
        m.node_stiffness.push_back(nodes[i].stiffness);
        m.node_size.push_back(nodes[i].size);
        m.node_offset.push_back(nodes[i].offset);
    }
    if (m.segments.empty()) throw InputError(fmt::format("contact surface '{}': nothing to merge", m.name));
    return m;
}

ContactSurface ContactSurface::rigid_part(const Mesh& mesh, std::string_view part, double depth) {
    if (!(depth > 0.0)) throw InputError(fmt::format("rigid contact surface '{}': depth {} must be > 0", part, depth));
    // Any material: the stiffness is discarded (a rigid side takes the deformable side's k).
    ContactSurface s = from_part(mesh, part, ElasticMaterial::make("rigid", 1.0, 0.0, 1.0));
    for (auto& seg : s.segments) {
        seg.stiffness = std::numeric_limits<double>::infinity();
        seg.depth = depth;
        seg.volume = 0.0;
    }
    s.nodes.clear();
    s.node_stiffness.clear();
    s.node_size.clear();
    s.node_offset.clear();
    s.rigid = true;
    return s;
}

std::size_t ContactSurface::remove_faces_on(const std::vector<int>& on) {
    const std::set<int> in(on.begin(), on.end());
    const std::size_t before = segments.size();
    std::erase_if(segments, [&](const Segment& s) {
        for (int a = 0; a < s.count; ++a)
            if (!in.count(s.n[a])) return false;
        return true;
    });
    std::set<int> used;
    for (const auto& s : segments)
        for (int a = 0; a < s.count; ++a) used.insert(s.n[a]);
    std::size_t k = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!used.count(nodes[i])) continue;
        nodes[k] = nodes[i], node_stiffness[k] = node_stiffness[i];
        if (!node_size.empty()) node_size[k] = node_size[i];
        if (!node_offset.empty()) node_offset[k] = node_offset[i];
        ++k;
    }
    nodes.resize(k), node_stiffness.resize(k);
    if (!node_size.empty()) node_size.resize(k);
    if (!node_offset.empty()) node_offset.resize(k);
    return before - segments.size();
}

double ContactSurface::mean_segment_size() const {
    if (segments.empty()) return 0.0;
    double s = 0.0;
    for (const auto& seg : segments) s += std::sqrt(seg.area);
    return s / static_cast<double>(segments.size());
}

}  // namespace fem::contact
