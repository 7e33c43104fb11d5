#pragma once
// Mesh helpers beyond mesh.hpp's structured generators (kept out of mesh.hpp, which most of the
// library includes): a graded quad4 grid on a plane, welding coincident nodes of meshes put
// together, and the node nearest to a point.
//
// Usage (a plate of rows a along u and columns b along v, welded to a second plate sharing its
// first rows; the node nearest to p among the plate's nodes):
//   Mesh plates = graded_parallelogram_quad4(origin, u, v, a, b, "plate");
//   plates.append(graded_parallelogram_quad4(origin, u, v, a2, b2, "track"));
//   weld_coincident_nodes(plates, 1e-9);
//   const int n = nearest_node(plates, p, plates.node_set("..."));
#include <span>
#include <string>

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

}  // namespace fem
