#pragma once
// The TOML case file of the fem-topopt program: a design domain (a rectangular grid or a Gmsh mesh
// of quadrilaterals), a plane-stress material and thickness, supports, point loads in load cases,
// passive regions and the optimization settings. Example (the short cantilever of thesis Table 2-11):
//
//   [domain]
//   type = "rectangle"          # or "gmsh" with mesh = "part.msh" (path relative to the case file)
//   size = [0.15, 0.1]          # m
//   elements = [75, 50]
//   element = "quad8"           # or "quad4"
//   thickness = 0.001           # m
//
//   [material]
//   E = 207e9                   # Pa
//   nu = 0.3
//
//   [optimization]
//   removed = 0.7               # volume fraction removed (or volume_fraction = 0.3, the fraction kept)
//   penalty = 3.0
//   filter = "sensitivity"      # none | sensitivity | density
//   filter_radius = 0.003       # m
//   min_stiffness = 1e-9        # E_min/E0 (E = E_min + x^p (E0 - E_min)), or instead
//                               # min_density = 1e-3: x >= x_min with E = x^p E0 (the 99-line code)
//   projection = "none"         # or "heaviside" (with filter = "density"): beta 1, 2, 4, ... up to
//   projection_beta_max = 32    #   projection_beta_max, doubled every 50 iterations or on convergence
//   move_limit = 0.2            # OC: per iteration; with projection on the physical densities (m / H'(eta), simp.hpp)
//   change_tolerance = 0.01
//   oc_tolerance = 1e-12        # OC bisection: relative width of the lambda bracket (88-line code: 1e-3)
//   max_iterations = 1000
//   solver = "auto"             # direct (sparse Cholesky) | multigrid (CG, structured quad4 grids) |
//                               #   auto: multigrid above 20,000 free DOF on a grid, direct otherwise
//   solver_tolerance = 1e-6     # multigrid-CG: stop at |f - K u| <= this |f|
//
//   [[support]]                 # node selection: edge = "x0"|"x1"|"y0"|"y1", node_set = "name",
//   edge = "x0"                 #   at = [x, y] (the node there), or box = [xmin, ymin, xmax, ymax]
//   fix = ["x", "y"]
//
//   [[load]]
//   at = [0.15, 0.05]           # same node selections as supports; the force acts on every node
//   force = [0.0, -3000.0]      # N
//   case = 1                    # load case (1, 2, ...); compliances of the cases are summed
//
//   [[passive]]
//   kind = "void"               # or "solid"
//   circle = [0.1, 0.05, 0.01]  # or box = [xmin, ymin, xmax, ymax]: elements whose centroid is inside
//
//   [output]
//   directory = "topopt-out"    # relative to the working directory
//
// Every mistake is an InputError naming the file, the line and the key (lib/input: wrong types,
// non-integers, out-of-range and non-finite values, unknown keys and keys that have no effect with
// the other settings, such as mesh on a rectangle or filter_radius with filter = "none"). A grid
// the machine cannot hold is refused before it is built, with the memory it would need.
#include <filesystem>
#include <string>
#include <string_view>

#include "mesh/mesh.hpp"
#include "topopt/model.hpp"
#include "topopt/simp.hpp"

namespace fem::topopt {

struct Case {
    Mesh mesh;
    Model model;
    Settings settings;
    std::filesystem::path output_directory = "topopt-out";
    std::string summary;  // what was read, for the program's first lines of output
};

/// Parses case-file text; `source` names it in messages and `base` is the folder that relative mesh
/// paths start from.
Case parse_case(std::string_view text, const std::string& source, const std::filesystem::path& base = ".");
/// Reads a case file (InputError when it cannot be opened).
Case read_case(const std::filesystem::path& path);

}  // namespace fem::topopt
