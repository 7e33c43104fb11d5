#pragma once
// Gmsh meshes in and out of fem::Mesh: the reader for users' .msh files (format 2.2 and 4.1, ASCII
// or binary) and the conversion of the current Gmsh model, which the tetrahedral finger meshers
// (mesh/finger.hpp) use after meshing a CAD geometry through the Gmsh API.
//
// How a Gmsh model becomes a fem::Mesh:
//   - nodes are renumbered 0, 1, 2, ... in increasing Gmsh node tag (deterministic);
//   - every physical group gives element blocks, one per (group, element type), whose part is the
//     group's name ("physical_<dim>_<tag>" when the group has no name). A model without physical
//     groups gives one block per element type, part "mesh";
//   - a physical group of points, curves or surfaces also gives a node set of that name (all nodes
//     of its elements), e.g. "root" and "tip" of a finger;
//   - lower-dimensional elements that only describe the boundary of higher-dimensional ones
//     (every node of the entity is a node of a higher-dimensional element: a clamped face, a
//     loaded edge) give a node set only, not an element block: otherwise the solver would see
//     shell elements on the face of a solid. A surface or curve that stands on its own (a shell
//     drum, a beam, a point mass) gives blocks;
//   - supported element types: point (Gmsh type 15), 2-node line (1), 3-node triangle (2), 4-node
//     quadrilateral (3), 8-node serendipity quadrilateral (16), 4-node tetrahedron (4), 10-node
//     tetrahedron (11), 8-node hexahedron (5). Any other type in a block is an InputError naming
//     the type and the group; in a boundary-only group any type is fine (only its nodes are used).
//
// Node order: Gmsh's node orders for these types are the library's (element_shape.hpp), so no
// permutation is applied. In particular the 10-node tetrahedron keeps Gmsh's mid-edge order
// 01, 12, 20, 03, 23, 13 (verified against gmsh::model::mesh::getElementProperties, which gives the
// reference coordinates of the ten nodes: node 8 at (0, 1/2, 1/2) = edge 23, node 9 at (1/2, 0, 1/2)
// = edge 13). VTK numbers the last two the other way round; io/vtu.cpp swaps them.
#include <filesystem>

#include "mesh/mesh.hpp"

namespace fem {

/// Scoped use of the Gmsh library (which is a process-wide singleton and not thread-safe): the
/// first live session initializes Gmsh, quiet (General.Terminal = 0, one thread), the last one
/// finalizes it; a session holds a process-wide recursive lock, so sessions nest within a thread
/// and serialize across threads. Every use of the gmsh API in the library goes through one.
///
/// The caller's OpenMP thread count survives the session: Gmsh calls omp_set_num_threads on the
/// calling thread (at gmsh::initialize, on the option General.NumThreads and in every mesh
/// generation; seen in gdb), which left every later parallel region of a program that meshes and
/// then solves on the same thread on one thread. A session saves omp_get_max_threads() when it starts
/// and restores it when it ends (inside a session the count is Gmsh's).
class GmshSession {
public:
    GmshSession();
    ~GmshSession();
    GmshSession(const GmshSession&) = delete;
    GmshSession& operator=(const GmshSession&) = delete;

private:
    int caller_threads_ = 1;  // omp_get_max_threads() of the calling thread when the session started
};

/// Reads a Gmsh .msh file (2.2 or 4.1, ASCII or binary) into a Mesh (see above for the rules).
/// Gmsh reads it in a separate reader process (see gmsh.cpp), so a crash inside Gmsh, or a read that
/// takes longer than the limit below, is an InputError too.
/// Throws InputError for a missing or unreadable file, a malformed file, a file without elements,
/// an unsupported element type, or a mesh that fails fem::validate (e.g. an inverted element).
Mesh read_gmsh(const std::filesystem::path& path);

/// How long Gmsh may take to read a file before read_gmsh refuses it as malformed: `base_seconds`
/// plus `seconds_per_megabyte` per MB of the file; by default 30 s + 10 s/MB, a margin of 100x or
/// more over Gmsh's reading speed. (libgmsh 4.8 spends minutes on a 1 kB binary MSH 4.1 file with a
/// huge count: found by tests/fuzz/fuzz_gmsh.) The fuzz target and tests set shorter limits.
void set_gmsh_read_time_limit(double base_seconds, double seconds_per_megabyte);

/// Converts the current Gmsh model (the caller holds a GmshSession and has meshed or opened it).
/// `source` names the model in error messages. Throws InputError when it has no elements.
Mesh mesh_from_gmsh_model(const std::string& source = "gmsh model");

}  // namespace fem
