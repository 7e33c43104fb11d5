#pragma once
// How far a finger reaches beyond the half objects' symmetry plane, where the mirrored half of a
// half model is (and the finger's mirror image: Scene::mirror_contact). The measure of
// football_sweep and ellipsoid_flip (README "Penetration" / "Fingers and the symmetry plane"),
// sampled by the studies every 0.1 ms.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "contact/surface.hpp"
#include "core/types.hpp"
#include "hand/scene.hpp"

namespace fem::hand {

/// [farthest distance beyond the plane (m), when (s), which node, first time beyond (s; -1: never)].
using PlaneExcursion = std::array<double, 4>;
inline constexpr PlaneExcursion kNoExcursion = {0.0, -1.0, -1.0, -1.0};

/// Updates b with the nodes' positions x at time t: a node is beyond the plane when z > plane_z
/// (the half objects keep z <= their cut plane).
inline void track_plane_excursion(std::span<const int> nodes, std::span<const Vec3> x, double plane_z, double t,
                                  PlaneExcursion& b) {
    for (int n : nodes) {
        const double d = x[n].z() - plane_z;
        if (d > 0.0 && b[3] < 0.0) b[3] = t;
        if (d > b[0]) b = {d, t, static_cast<double>(n), b[3]};
    }
}

/// The surface nodes of finger `finger` ("A".."E"; part "finger-<finger>"): the nodes a finger can
/// push beyond the plane with, and those of the studies' finger-finger clearance.
inline std::vector<int> finger_surface_nodes(const HandModel& hm, const std::string& finger) {
    return contact::ContactSurface::from_part(hm.mesh(), "finger-" + finger, hm.scene().hand.rubber).nodes;
}

}  // namespace fem::hand
