#pragma once
// Contact surfaces (thesis Sec 2.3.6): the master segments and slave nodes of a part, with the
// penalty stiffness of Eq 2-30.
//
// A solid part's surface is the set of element faces used by exactly one element of the part
// (hex8: quadrilaterals; tet4/tet10: the corner triangles), oriented outward. Each face becomes a
// master segment carrying k = s_f B A^2 / V (Eq 2-30a; B = E / (3 (1 - 2 nu)), Eq 2-33; A the face
// area, V the volume of the element that owns it). Shell elements (quad4/tri3) are segments
// themselves with k = s_f B A / max diagonal (Eq 2-30b), normal as numbered. The slave nodes are
// the nodes of the surface faces; each carries the smallest k of the faces around it.
//
// A rigid surface (a drum, a fixed object, the ground) is a ContactSurface whose segment nodes are
// its own points (RigidSurface::points, not mesh nodes) moved by a RigidMotion (rigid.hpp); its
// stiffness is infinite, so a pair takes the deformable side's k.
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

/// One master segment: a quadrilateral (count 4, bilinear) or a triangle (count 3). Node indices
/// refer to the mesh (deformable surface) or to RigidSurface::points (rigid surface).
struct Segment {
    std::array<int, 4> n{-1, -1, -1, -1};
    int count = 4;
    double stiffness = std::numeric_limits<double>::infinity();  // k of Eq 2-30 [N/m]
    double depth = std::numeric_limits<double>::infinity();      // deepest penetration still taken as contact [m]
    double area = 0.0;     // reference face area [m^2]
    double volume = 0.0;   // owning element's reference volume [m^3] (0 for shells and rigid faces)
    int block = -1, element = -1;  // owning element (-1: rigid)
};

struct ContactSurface {
    std::string name;                     // part name (for messages and outputs)
    std::vector<Segment> segments;
    std::vector<int> nodes;               // slave candidates: every node of a segment, sorted
    std::vector<double> node_stiffness;   // per entry of `nodes`: smallest k of its segments
    bool rigid = false;

    /// The outer surface of every solid (hex8, tet4, tet10) and shell (quad4, tri3) block of `part`,
    /// with Eq 2-30 stiffness for `material` and scale factor s_f. The penetration depth limit of a
    /// segment is half the owning element's thickness V / A (shells: half the largest diagonal):
    /// deeper nodes are taken to be on the far side. Throws InputError when the part has no
    /// surface elements.
    static ContactSurface from_part(const Mesh& mesh, std::string_view part, const ElasticMaterial& material,
                                    double scale_factor = 1.0);
    /// One surface from several deformable parts' surfaces (e.g. every finger of a hand against one
    /// object: one interface, one search, and one stable-step bound instead of one per finger).
    /// The parts must not share nodes; throws InputError naming the parts otherwise.
    static ContactSurface merge(std::string name, const std::vector<ContactSurface>& parts);
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
