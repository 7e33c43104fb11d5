#pragma once
// The central-difference node update of ExplicitSolver::run() (thesis Eq 2-5 with the lumped mass,
// mass-proportional damping of Eq 2-39 at the mid-point, constraints) and its energy sums, over one
// chunk of nodes. Its own file so that it can be compiled for AVX-512, AVX2 and baseline x86-64 and
// chosen at load time (GCC function multi-versioning, as the element kernels). The free nodes are
// updated in vector loops (8 nodes per AVX-512 instruction; the three divisions by 1 + a of a damped
// node had made the scalar update ~18 % of football Case 4's samples), their terms of the eleven
// energy sums then added node by node in node order; constrained nodes take the scalar update_node.
// Every version does the same IEEE operations in the same order (no FMA: the .cpp sets
// fp-contract=off; plain arrays, no Eigen): the same bits on every processor, and as update_node.
#include <array>
#include <vector>

#include "core/types.hpp"

namespace fem::explicit_detail {

/// What the update of one chunk of nodes adds to the energy bookkeeping (see ExplicitSolver::run()).
struct NodeSums {
    double ke = 0, ke_plus = 0, damp = 0, wext = 0, wabs = 0, damp_half = 0, wext_half = 0;
    double wprov = 0, wprov_half = 0, visc = 0, visc_half = 0;
    int bad = -1;  // first node whose new kinetic energy is not finite
};

/// The solver's nodal arrays the update reads and writes (node-major Vec3 arrays as in NodalState).
struct NodeUpdateData {
    const double* mass;
    const double* alpha;                       // mass damping per node
    const unsigned* fixed;                     // per node: fixed DOF mask (bits 0-2: translations)
    const int* target_index;                   // per node: index into target, or -1
    const std::array<double, 3>* target;       // prescribed velocity over the coming step (NaN: free)
    const Vec3* f;                             // internal forces
    const Vec3* fext;                          // loads (zeros when there are none)
    const Vec3* fprov;                         // force providers (contact; read only when `providers`)
    const Vec3* fv;                            // viscous part of f (read only when `book_viscous`)
    Vec3* v;                                   // v(n-1/2) in, v(n+1/2) out
    Vec3* x;                                   // x(n) in, x(n+1) out
    bool loads = false, providers = false, book_viscous = false;
    double dtavg = 0, dt_half = 0;             // (dt(n-1/2) + dt(n+1/2))/2, dt(n+1/2)
};

/// Updates nodes [i0, i1) and returns their energy sums (in node order). Vectorized over the free
/// nodes; the same bits as update_node on each node in order (test ExplicitNodeUpdate.*).
NodeSums update_nodes(const NodeUpdateData& d, int i0, int i1);

/// The scalar update of node i (any node: free, massless, fixed or prescribed), its terms added to
/// p in the order update_nodes adds them: the reference of the vectorized update.
void update_node(const NodeUpdateData& d, int i, NodeSums& p);

}  // namespace fem::explicit_detail
