#pragma once
// Mesh helpers beyond mesh.hpp's structured generators (kept out of mesh.hpp, which most of the
// library includes): a graded quad4 grid on a plane, welding coincident nodes of meshes put
// together, the node nearest to a point, and renumbering the nodes for locality.
//
// Usage (a plate of rows a along u and columns b along v, welded to a second plate sharing its
// first rows; the node nearest to p among the plate's nodes):
//   Mesh plates = graded_parallelogram_quad4(origin, u, v, a, b, "plate");
//   plates.append(graded_parallelogram_quad4(origin, u, v, a2, b2, "track"));
//   weld_coincident_nodes(plates, 1e-9);
//   const int n = nearest_node(plates, p, plates.node_set("..."));
#include <span>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace fem {

/// Quad4 grid with node (i, j) = origin + a[i] u + b[j] v (i < a.size(), j < b.size()), numbered
/// j a.size() + i, elements counter-clockwise about u x v, part `part`. `a` and `b` must increase
/// strictly (at least two values each) and u, v must not be parallel; InputError naming `part`
/// otherwise. parallelogram_quad4 is this grid with a[i] = i/nu - 1/2, b[j] = j/nv - 1/2.
Mesh graded_parallelogram_quad4(const Vec3& origin, const Vec3& u, const Vec3& v, std::span<const double> a,
                                std::span<const double> b, std::string part);

/// Merges nodes whose coordinates round to the same multiple of `tol` (each onto the first of
/// them, in node order), renumbers the elements and node sets (duplicates in a set removed) and
/// drops the merged nodes: the kept nodes keep their order. Returns the number of nodes removed.
int weld_coincident_nodes(Mesh& mesh, double tol);

/// The node of `candidates` nearest to p (the first of equally near ones); InputError when there
/// is none.
int nearest_node(const Mesh& mesh, const Vec3& p, std::span<const int> candidates);
/// The node of the whole mesh nearest to p (the first of equally near ones).
int nearest_node(const Mesh& mesh, const Vec3& p);

// --- node order -------------------------------------------------------------------------------------
//
// Why: an explicit step gathers every element's nodal coordinates and velocities and scatters its
// forces back; when the nodes of neighbouring elements lie far apart in the nodal arrays, each
// element touches new cache lines. Gmsh numbers a second-order mesh's mid-edge nodes after all its
// corner nodes, so every tet10 reaches two distant parts of the arrays (the chicken of Ch 5: the
// gather / scatter cost 1.3 x the element kernel). Reverse Cuthill-McKee (Cuthill and McKee 1969;
// George and Liu 1981, Sec 4.3) numbers the nodes level by level from a pseudo-peripheral node, so
// that an element's nodes get nearby numbers (small bandwidth). The explicit groups sort their
// elements by their smallest node (par::node_order), so the elements follow the new order too.
// A renumbering changes results only at round-off (the order in which element forces are summed
// into a node).
//
// Usage (a Gmsh mesh renumbered before it is solved):
//   Mesh m = mesh_from_gmsh_model("finger");
//   renumber_nodes(m, reverse_cuthill_mckee(m));

/// The reverse Cuthill-McKee order of the mesh's nodes: order[k] is the old number of new node k.
/// Two nodes are neighbours when an element holds both. Each connected part is numbered from a
/// pseudo-peripheral node of least degree (George-Liu), neighbours in increasing degree; parts in the
/// order of their smallest old node, nodes of no element alone at their place in that order; ties
/// go to the smaller old number (deterministic).
std::vector<int> reverse_cuthill_mckee(const Mesh& mesh);

/// Largest |i - j| over the node pairs of an element (the nodal bandwidth the order gives).
int node_bandwidth(const Mesh& mesh);

/// Renumbers the nodes: old node order[k] becomes node k. Coordinates move, element connectivity
/// and every node set are mapped (a set keeps its nodes in their order); blocks, parts, element
/// order and element ids stay. InputError when `order` is not a permutation of the nodes.
void renumber_nodes(Mesh& mesh, std::span<const int> order);

/// Mirrors the mesh through the plane through `point` with normal `normal` (any length > 0), and
/// renumbers each element's nodes so that solids keep a positive volume and shells their normal
/// mirrored with them (a mirror image is left-handed: tet4/tet10 swap corners 1 and 2 and their
/// edges, hex8 swaps its two faces 0123 and 4567, quad4/tri3 reverse their order). E.g. the half
/// bird of Step 3 of chicken_shackling, meshed on its z >= 0 side, put on the hand's side z <= 0.
/// Node numbers and node sets are kept. InputError for a zero normal or a shape without a rule
/// (quad8, hex20).
void reflect(Mesh& mesh, const Vec3& point, const Vec3& normal);

}  // namespace fem
