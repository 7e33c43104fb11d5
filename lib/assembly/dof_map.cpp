#include "assembly/dof_map.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include "core/error.hpp"

namespace fem {

void DofMap::require(int node, int dofs) {
    if (node < 0 || node >= node_count())
        throw InputError("DOF request for node " + std::to_string(node) + ", which does not exist");
    if (dofs != 3 && dofs != 6) throw InputError("a node carries 3 or 6 DOFs, not " + std::to_string(dofs));
    if (dofs > count_[node]) count_[node] = dofs;
}

void DofMap::finalize() {
    first_.assign(count_.size(), 0);
    size_ = 0;
    for (std::size_t n = 0; n < count_.size(); ++n) {
        first_[n] = size_;
        size_ += count_[n];
    }
}

void Constraints::fix(int node, DofMask components) { fixes_.emplace_back(node, components); }

void Constraints::couple(const std::vector<int>& nodes, DofMask components) {
    if (nodes.size() >= 2) couplings_.emplace_back(nodes, components);
}

Constraints::Reduction Constraints::reduce(const DofMap& dofs) const {
    const int n = dofs.size();
    // Union-find over full DOFs: a coupling joins DOFs into one group; a group with a fixed member
    // is fixed as a whole (coupling to a support is a support).
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::vector<char> fixed(n, 0);
    auto check_node = [&](int node, const char* what) {
        if (node < 0 || node >= dofs.node_count())
            throw InputError(std::string(what) + " names node " + std::to_string(node) + ", which does not exist");
    };
    for (const auto& [node, mask] : fixes_) {
        check_node(node, "a support");
        for (int c = 0; c < 6; ++c)
            if ((mask >> c & 1u) && dofs.dof(node, c) >= 0) fixed[dofs.dof(node, c)] = 1;
    }
    Reduction r;
    for (const auto& [nodes, mask] : couplings_) {
        for (int c = 0; c < 6; ++c) {
            if (!(mask >> c & 1u)) continue;
            int first = -1;
            for (int node : nodes) {
                check_node(node, "a coupling");
                const int d = dofs.dof(node, c);
                if (d < 0)
                    throw InputError("a coupling of component " + std::to_string(c) + " names node " + std::to_string(node) +
                                     ", which carries " + std::to_string(dofs.dofs(node)) +
                                     " DOFs (is it outside every element, or a solid node asked for a rotation?)");
                if (first < 0) first = d;
                else {
                    const int a = root(first), b = root(d);
                    if (a != b) parent[std::max(a, b)] = std::min(a, b);
                }
            }
        }
    }
    for (int i = 0; i < n; ++i)
        if (fixed[i]) fixed[root(i)] = 1;
    // Number the groups in the order of their first (lowest) DOF: the root is the lowest member.
    r.reduced_of_full.assign(n, -1);
    for (int i = 0; i < n; ++i) {
        const int g = root(i);
        if (fixed[g]) {
            ++r.fixed;
            continue;
        }
        if (g == i) r.reduced_of_full[i] = r.size++;
        else {
            r.reduced_of_full[i] = r.reduced_of_full[g];
            ++r.coupled;
        }
    }
    return r;
}

}  // namespace fem
