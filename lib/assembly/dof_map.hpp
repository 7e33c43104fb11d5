#pragma once
// Degrees of freedom of a mesh whose nodes carry 3 (solid: ux, uy, uz) or 6 (shell: ux, uy, uz, rx,
// ry, rz) DOFs, and their reduction by supports and couplings.
//
// Full DOFs are numbered node after node; a node carries the largest count any element touching it
// asks for (a solid node shared with a shell gets 6; its rotations then see only the shell's
// stiffness). Fixed DOFs are eliminated; coupled DOFs (ANSYS CP sets: the thesis models every screw
// of the portal frame, Sec 2.4.2, as a set of coupled DOFs) share one equation, i.e. master-slave
// elimination u_slave = u_master, which is K_red = T^T K T with a 0/1 matrix T.
#include <vector>

namespace fem {

/// Components of a nodal DOF.
enum Dof : int { UX = 0, UY = 1, UZ = 2, RX = 3, RY = 4, RZ = 5 };

/// A set of components as a bit mask: bit c stands for component c.
using DofMask = unsigned;
inline constexpr DofMask kTranslations = 0b000111;
inline constexpr DofMask kRotations = 0b111000;
inline constexpr DofMask kAllDofs = 0b111111;
inline constexpr DofMask dof_bit(Dof d) { return 1u << d; }

class DofMap {
public:
    DofMap() = default;
    explicit DofMap(int node_count) : count_(node_count, 0) {}

    /// Node `node` needs at least `dofs` DOFs (3 or 6); call before finalize().
    void require(int node, int dofs);
    /// Numbers the DOFs node after node.
    void finalize();

    int node_count() const { return static_cast<int>(count_.size()); }
    /// DOFs of the node (0 for a node that no element touches).
    int dofs(int node) const { return count_[node]; }
    /// Full index of component c of the node; -1 when the node has no such component.
    int dof(int node, int component) const {
        return component < count_[node] ? first_[node] + component : -1;
    }
    int size() const { return size_; }

private:
    std::vector<int> count_, first_;
    int size_ = 0;
};

/// Supports and couplings, stated on (node, component) pairs and resolved against a DofMap.
class Constraints {
public:
    /// Fixes the given components of the node (components the node does not carry are skipped:
    /// "fix all" on a solid node fixes its three translations).
    void fix(int node, DofMask components = kAllDofs);
    /// Couples the given components of every node in `nodes` (one CP set per component).
    void couple(const std::vector<int>& nodes, DofMask components = kTranslations);

    /// The reduction: reduced index of every full DOF (-1 when fixed), and the reduced size.
    /// Throws InputError when a coupling names a component a node does not carry.
    struct Reduction {
        std::vector<int> reduced_of_full;
        int size = 0;
        int fixed = 0;    // full DOFs eliminated by supports (including those coupled to one)
        int coupled = 0;  // full DOFs eliminated as slaves of a coupling
    };
    Reduction reduce(const DofMap& dofs) const;

    bool empty() const { return fixes_.empty() && couplings_.empty(); }
    /// The constraints as stated (for writers such as deck::write_deck): (node, components) fixed,
    /// (nodes, components) coupled.
    const std::vector<std::pair<int, DofMask>>& fixes() const { return fixes_; }
    const std::vector<std::pair<std::vector<int>, DofMask>>& couplings() const { return couplings_; }

private:
    std::vector<std::pair<int, DofMask>> fixes_;
    std::vector<std::pair<std::vector<int>, DofMask>> couplings_;
};

}  // namespace fem
