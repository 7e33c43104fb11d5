#pragma once
// Contact surfaces (thesis Sec 2.3.6): the master segments and slave nodes of a part, with the
// penalty stiffness of Eq 2-30.
//
// A solid part's surface is the set of element faces used by exactly one element of the part
// (hex8: quadrilaterals; tet4/tet10: the corner triangles), oriented outward. Each face becomes a
// master segment carrying k = s_f B A^2 / V (Eq 2-30a; B = E / (3 (1 - 2 nu)), Eq 2-33; A the face
// area, V the volume of the element that owns it). Shell elements (quad4/tri3) are segments
// themselves with k = s_f B A / max diagonal (Eq 2-30b). The slave nodes are the nodes of the
// surface faces; each carries the smallest k of the faces around it.
//
// Shell thickness (from_part's shell_thickness t > 0), as LS-DYNA's automatic contacts treat shells:
// a shell segment is two-sided and its contact surfaces are offset by t/2 on either side of the
// mid-surface; a node touches the side it approaches from (the side it is on when it first comes
// within the offset, kept while the contact lasts, so a node pushed past the mid-surface is still
// pushed back to its own side); and a shell part's slave nodes carry their own offset t/2, so two
// shells touch when their mid-surfaces are (t1 + t2)/2 apart and a shell rests on a solid face at
// t/2. The penetration is measured from the offset surface: g = side (x - p) . n - t_m/2 - t_s/2.
// Without a thickness (t = 0) a shell segment is one-sided at its mid-surface, normal as numbered
// (the earlier behaviour, kept for parts whose thickness contact should ignore).
//
// A rigid surface (a drum, a fixed object, the ground, a pallet) is the surface of a rigid part of the
// explicit model (ExplicitModel::add_rigid_part: the solver moves its nodes by its RigidMotion):
// ContactSurface::rigid. Its stiffness is infinite, so a pair takes the deformable side's k; it is
// a master only (no slave nodes).
#include <array>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.hpp"
#include "material/elastic.hpp"
#include "mesh/mesh.hpp"

namespace fem::contact {

/// One master segment: a quadrilateral (count 4, bilinear) or a triangle (count 3); node indices
/// into the mesh.
struct Segment {
    std::array<int, 4> n{-1, -1, -1, -1};
    int count = 4;
    double stiffness = std::numeric_limits<double>::infinity();  // k of Eq 2-30 [N/m]
    double depth = std::numeric_limits<double>::infinity();      // deepest penetration still taken as contact [m]
    double area = 0.0;     // reference face area [m^2]
    double volume = 0.0;   // owning element's reference volume [m^3] (0 for shells and rigid faces)
    double offset = 0.0;   // half the shell thickness: the contact surfaces' distance from the face [m]
    bool two_sided = false;  // a shell with thickness: contact from either side
    int block = -1, element = -1;  // owning element (-1: rigid)
};

struct ContactSurface {
    std::string name;                     // part name (for messages and outputs)
    std::vector<Segment> segments;
    std::vector<int> nodes;               // slave candidates: every node of a segment, sorted
    std::vector<double> node_stiffness;   // per entry of `nodes`: smallest k of its segments
    // Per entry of `nodes`: the local element size, the smallest over its faces of the owning
    // element's thickness V / A normal to the face (shells: sqrt(A)); penetrations are reported as
    // a fraction of it.
    std::vector<double> node_size;
    std::vector<double> node_offset;      // per entry of `nodes`: half its shells' thickness (0: solid)
    bool rigid = false;

    /// The outer surface of every solid (hex8, tet4, tet10) and shell (quad4, tri3) block of `part`,
    /// with Eq 2-30 stiffness for `material` and scale factor s_f. The penetration depth limit of a
    /// segment is half the owning element's thickness V / A (shells: half the largest diagonal,
    /// measured from the offset surface): deeper nodes are taken to be on the far side.
    /// shell_thickness > 0: the part's shells are two-sided with that thickness (see above). Throws
    /// InputError when the part has no surface elements or the thickness is negative.
    static ContactSurface from_part(const Mesh& mesh, std::string_view part, const ElasticMaterial& material,
                                    double scale_factor = 1.0, double shell_thickness = 0.0);
    /// The outer surface of the rigid part `part` (solid or shell blocks, ExplicitModel::add_rigid_part)
    /// as a rigid master: infinite stiffness, penetration depth limit `depth` [m] (deeper nodes are
    /// taken to be on the far side; a fraction of the body's thickness), no slave nodes. Throws
    /// InputError for depth <= 0 or a part without surface elements.
    /// One surface from several deformable parts' surfaces (e.g. every finger of a hand against one
    /// object: one interface, one search, and one stable-step bound instead of one per finger).
    /// The parts must not share nodes; throws InputError naming the parts otherwise.
    static ContactSurface merge(std::string name, const std::vector<ContactSurface>& parts);
    static ContactSurface rigid_part(const Mesh& mesh, std::string_view part, double depth);
    /// Leaves out the segments whose nodes all belong to `nodes`, and the slave nodes then on no
    /// segment: e.g. the cut face of a half model on its symmetry plane, where the mirrored half is,
    /// not a surface. The remaining nodes keep their stiffness and size (taken over all their faces:
    /// the smaller, safe for the step). Returns the number of segments removed.
    std::size_t remove_faces_on(const std::vector<int>& nodes);
    /// Smallest / mean segment size (square root of area): for margins and cell sizes.
    double mean_segment_size() const;
};

/// Bulk modulus of Eq 2-33.
inline double bulk_modulus(const ElasticMaterial& m) { return m.youngs_modulus / (3.0 * (1.0 - 2.0 * m.poissons_ratio)); }

/// Eq 2-30a: k = s_f B A^2 / V.
inline double solid_penalty_stiffness(double B, double area, double volume, double sf = 1.0) {
    return sf * B * area * area / volume;
}
/// Eq 2-30b: k = s_f B A / max(shell diagonal).
inline double shell_penalty_stiffness(double B, double area, double max_diagonal, double sf = 1.0) {
    return sf * B * area / max_diagonal;
}

/// Area of a segment (quad: bilinear, 2x2 Gauss; triangle: exact) at the given coordinates.
double segment_area(const Segment& s, std::span<const Vec3> x);
/// Volume of a hex8 (trilinear, 2x2x2 Gauss, exact) or a tetrahedron (corner nodes).
double element_volume(ElementShape shape, std::span<const Vec3> corner_coords);

}  // namespace fem::contact
