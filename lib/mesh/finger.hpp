#pragma once
// Meshes of the compliant rubber finger of thesis Chapter 3 (Table 3-1: elliptical cross-section
// with semi-axes 12 mm and 8.45 mm, lengths 3, 4.5, 6 and 8 inch, clamped at its root), for the
// modelling comparison of Sec 3.3 (Table 3-2, Cases A-D, Fig 3-4) and the modal model of Fig 3-2.
//
// Frame (all meshes here): the major semi-axis a lies along x, the minor semi-axis b along y, the
// finger axis along z; the clamped root face is z = 0 and the free tip face z = L. Studies rotate or
// translate the mesh into their own frame. SI units (metres).
//
// Node sets of every finger mesh: "root" (the clamped face z = 0), "tip" (the free face z = L) and
// "tip_center" (one node: the centre of the tip face, or the tip node nearest to it).
#include <string>
#include <vector>

#include "core/units.hpp"
#include "material/elastic.hpp"
#include "mesh/mesh.hpp"

namespace fem::finger {

// --- Table 3-1 ------------------------------------------------------------------------------------
inline constexpr double semi_major_axis = 12.0 * units::mm;   // a
inline constexpr double semi_minor_axis = 8.45 * units::mm;   // b
/// The four finger lengths of Table 3-1 (3, 4.5, 6, 8 inch), in metres.
std::vector<double> table_3_1_lengths();
/// The finger rubber of Table 3-1: E 6.1 MPa (Table 3-7 also runs 4.2 MPa), nu 0.49, rho 1000 kg/m3.
ElasticMaterial rubber(double youngs_modulus = 6.1 * units::MPa);

/// The simplified finger: an elliptic cylinder (Cases A-C of Sec 3.3).
struct EllipticCylinder {
    double a = semi_major_axis;       // semi-axis along x [m]
    double b = semi_minor_axis;       // semi-axis along y [m]
    double length = 4.5 * units::inch;  // along z [m]
};

// --- structured hexahedral mesh (Cases A and B) ------------------------------------------------------

/// Layout of the structured cross-section, extruded along z into hexahedra. The cross-section is an
/// O-grid: an inner nx x ny block (a transfinite patch whose sides bulge towards the ellipse) inside
/// nr layers of quadrilaterals that run out to the ellipse. The 2 (nx + ny) boundary nodes are spaced
/// evenly in arc length. Why an O-grid: a single mapped block (what a mapped mesher puts on an
/// ellipse, and what the thesis's Case A counts suggest: 725 = 25 x 29 elements, 1080 = 36 x 30
/// nodes, i.e. 5 x 5 per cross-section) has elements with a ~180 degree corner where the block's
/// corners sit on the smooth boundary; their small V/A_max sets the whole model's time step
/// (Table 2-1, Sec 2.3.5). nr = 0 with inner_scale = 1 and bulge = 1 is that single mapped block.
struct HexCrossSection {
    int nx = 4;                 // inner-block elements along x
    int ny = 2;                 // inner-block elements along y
    int nr = 1;                 // radial layers of the ring (0: single mapped block)
    double inner_scale = 0.5;   // the inner block's corners sit on the ellipse scaled by this
    double bulge = 0.5;         // inner-block sides: 0 straight, 1 on the scaled ellipse
    double corner_shift = 0.0;  // block corners moved along the boundary by this fraction of the perimeter
};

/// The O-grid layout for a target element length h: the most uniform cross-section (largest
/// smallest-element size relative to the mean size, Table 2-1's A / longest side for the extruded
/// hexahedron) among layouts whose element count is within [0.8, 1.25] x (pi a b / h^2), whose
/// quads all have corner angles within 30..150 degrees (scaled Jacobian >= 0.5) and no side longer
/// than 1.5 h. A brute-force search over (nx, ny, nr, inner_scale, bulge): milliseconds.
HexCrossSection choose_hex_cross_section(const EllipticCylinder& g, double element_length);

/// The single mapped n x n block with its corners on the axes (corner_shift 1/8), the layout a
/// mapped mesher puts on an ellipse split into quarter arcs: the reconstruction of the thesis's
/// Case A (n = 5) and Case B (n = 9) cross-sections.
HexCrossSection mapped_cross_section(int n);

/// Hexahedral finger: the cross-section `section` extruded into `layers` equal layers along z.
Mesh hex_finger(const EllipticCylinder& g, const HexCrossSection& section, int layers, std::string part = "finger");

/// Hexahedral finger with target element length h: choose_hex_cross_section() and round(L / h)
/// layers.
Mesh hex_finger(const EllipticCylinder& g, double element_length, std::string part = "finger");

// --- tetrahedral meshes through Gmsh (Cases C and D, Fig 3-2) ------------------------------------------

struct TetOptions {
    double element_length = 4.0 * units::mm;  // target size h (Gmsh Mesh.MeshSizeMin = Max)
    int order = 1;                             // 1: tet4, 2: tet10 (mid-edge nodes on the true geometry)
    std::string part = "finger";
    /// Read h as Table 3-2's "average element length": the edge of the regular tetrahedron whose
    /// volume is the mean element volume. Gmsh meshes once at size h, then once more at the size
    /// scaled to meet that mean (Gmsh's tetrahedra come out ~15 % larger than asked). false: one
    /// mesh at Gmsh size h.
    bool match_mean_volume = true;
    /// Gmsh's 3D algorithm (Mesh.Algorithm3D: 1 Delaunay, 10 HXT; Debian's Gmsh has no Netgen, which
    /// Frontal needs) and whether its
    /// tetrahedron optimiser runs (Mesh.Optimize): the defaults make the study's meshes; the others
    /// let finger_damping --tet-step-rules try other meshers' meshes of the same finger.
    int algorithm_3d = 1;
    bool optimize = true;
};

/// Tetrahedral elliptic cylinder (OpenCASCADE kernel, Delaunay with Gmsh's optimiser), meshed by
/// Gmsh with a node embedded at the tip centre.
Mesh tet_finger(const EllipticCylinder& g, const TetOptions& options);

/// Case D, "the detailed model" (Sec 3.3): the thesis shows it only in Fig 3-4/3-7 and says it has
/// ribs and "a larger cross-section close to the fixed end" (observation 5), "the taper fixed-end
/// cross section" (Sec 4.2), and that its small features make the element lengths non-homogeneous
/// (observation 3); the real finger also carries a magnet (4 mm radius, 1.65 mm high) in its tip
/// (Sec 3.4). None is dimensioned. This reconstruction, every number a parameter:
///   - the elliptic body of Table 3-1 (a, b) from the end of the taper to the tip;
///   - a root taper: a ruled loft from the ellipse scaled by root_scale at z = 0 to (a, b) at
///     z = taper_length;
///   - circumferential ribs: rib_count elliptic rings, rib_height proud of the body (semi-axes
///     a + h, b + h) and rib_width long in z, evenly spaced over the untapered length;
///   - optionally the magnet pocket, a cylinder cut into the tip face (left out by default: the
///     magnet fills it).
/// The default sizes are guesses sized by one clue: at Case C's size our mesher reproduces Table
/// 3-2's element count to 0.1 % (h = edge of the regular tetrahedron of mean element volume), and
/// read the same way Case D's 23147 elements at 2.8 mm fill ~60 cm^3, 1.6 x the simplified finger
/// (an upper bound: small features refine the mesh locally). These defaults give 1.3 x.
struct DetailedFinger {
    EllipticCylinder body{};
    double root_scale = 1.5;                    // root semi-axes / body semi-axes
    double taper_length = 35.0 * units::mm;
    int rib_count = 6;
    double rib_height = 2.5 * units::mm;
    double rib_width = 4.0 * units::mm;
    bool magnet_pocket = false;
    double magnet_radius = 4.0 * units::mm;     // Sec 3.4
    double magnet_height = 1.65 * units::mm;    // Sec 3.4
};

/// Tetrahedral mesh of the detailed finger (Gmsh, OpenCASCADE kernel).
Mesh detailed_finger(const DetailedFinger& g, const TetOptions& options);

/// Exact volume of the reconstructed detailed finger's geometry (before meshing), for tests.
double detailed_finger_volume(const DetailedFinger& g);

// --- Table 3-2: the four modelling cases ------------------------------------------------------------

/// One case of Table 3-2 as the text defines it (Sec 3.3 list and table): the model and the mesh
/// request. The thesis's results (nodes, elements, dt, steps) are reference values: they live in
/// reference/<study>.toml, not here.
struct ModelingCase {
    std::string id;               // "A" .. "D"
    std::string description;      // the thesis's words
    ElementShape shape;           // Hex8 or Tet10 (see note)
    double element_length;        // "average element length" [m]
    bool detailed;                // Case D: the detailed geometry
    double finger_length;         // 4.5 inch for every case
    std::string note;
};
std::vector<ModelingCase> table_3_2_cases();

/// The mesh of a case: hex_finger (A, B), tet_finger (C), detailed_finger (D).
Mesh mesh_case(const ModelingCase& c, std::string part = "finger");

// --- quality ------------------------------------------------------------------------------------------

/// Shape measures of the solid elements of a mesh (hex8, tet4, tet10; other shapes are skipped).
struct MeshQuality {
    int solid_elements = 0;
    double volume = 0.0;                 // sum of element volumes (exact for hex8/tet4, 27-point for tet10)
    double min_scaled_jacobian = 1.0;    // corner scaled Jacobian (1 for a cube / regular tet)
    int worst_block = -1, worst_element = -1;
    double min_jacobian_ratio = 1.0;     // tet10: min det J / det J of the straight tet (corners, centre)
    double min_edge = 0.0, mean_edge = 0.0, max_edge = 0.0;  // corner-to-corner edges
    /// Smallest characteristic length of Table 2-1 (hexahedron V / A_max, tetrahedron minimum
    /// altitude, tet10 from its corners), the element that sets the explicit time step. Same
    /// definition as cfl::characteristic_length, which lives in fem_element (a library that
    /// depends on this one); tests/mesh checks that the two agree.
    double min_characteristic_length = 0.0;
    int shortest_block = -1, shortest_element = -1;
};
MeshQuality mesh_quality(const Mesh& mesh);

}  // namespace fem::finger
