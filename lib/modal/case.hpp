#pragma once
// A modal case file (TOML) for the fem-modal program: mesh, materials per part, supports and
// couplings by physical group, number of modes. Example (paths relative to the case file):
//
//   mesh = "frame.msh"          # Gmsh 2.2 or 4.1; physical groups give parts and node sets
//   modes = 30
//   shift_hz = 0.0              # < 0 for a free structure (rigid-body modes), see modal.hpp
//   mass = "consistent"         # or "lumped"
//   tet_mass_rule = "exact"     # consistent mass of tet4/tet10: "exact" or "ccx" (integrated with
//                               # the stiffness rule, 1 / 4 points, as CalculiX's C3D4 / C3D10)
//   output = "frame_modes"      # folder for frequencies.csv, modes.h5, modes.pvd (+ VTUs)
//   shapes = 5                  # mode shapes written (VTU + modes.h5): the first 5; 0 = frequencies
//                               # only; default all
//
//   [materials.steel]
//   E = 210e9                   # Pa
//   nu = 0.28
//   rho = 7700.0                # kg/m^3
//
//   [[parts]]                   # every element block of the mesh must belong to a listed part
//   name = "plate"              # physical group name
//   material = "steel"
//   thickness = 0.002           # only for shell parts (quad4, MITC4)
//   element = "C3D8"            # formulation, named as CalculiX/Abaqus name it (modal/deck_run.hpp):
//                               # hex8 "C3D8I" (incompatible modes as ccx's C3D8I, bubble
//                               # DOFs with mass; default) or "C3D8" (fully integrated trilinear); hex20 "C3D20" (3x3x3 Gauss, default) or
//                               # "C3D20R" (2x2x2); tet10 "C3D10"; tet4 "C3D4"; quad4 shells "S4"
//
//   [[supports]]
//   set = "base"                # physical group giving a node set
//   dofs = ["ux", "uy", "uz"]   # default: all DOFs the nodes carry
//
//   [[couplings]]               # ANSYS CP sets: the screws of thesis Sec 2.4.2
//   sets = ["screw1_plate", "screw1_bracket"]   # node pairs at coincident places ...
//   # set = "screw1"                            # ... or all nodes of one set share the DOFs
//   dofs = ["ux", "uy", "uz"]   # default translations
//
// Every setting takes effect as written or is refused: a misspelt key, a value of the wrong type
// (modes = 2.5), out of range (modes = 0, nu = 0.5) or not finite (E = nan) is an InputError naming
// the file, the line and the key.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "assembly/dof_map.hpp"
#include "assembly/model.hpp"
#include "element/solid_elements.hpp"
#include "material/elastic.hpp"
#include "modal/modal.hpp"

namespace fem::modal {

struct CasePart {
    std::string name;
    ElasticMaterial material;
    double thickness = 0.0;  // > 0 for shells
    std::string element;     // deck element type ("C3D8"); empty = the default for the mesh's shape
};
struct CaseSupport {
    std::string set;
    DofMask dofs = kAllDofs;
};
struct CaseCoupling {
    std::vector<std::string> sets;  // one set (couple all its nodes) or two (coincident pairs)
    DofMask dofs = kTranslations;
};

struct ModalCase {
    std::filesystem::path mesh, output;
    ModalOptions options;
    solid::MassKind mass = solid::MassKind::Consistent;
    bool tet_mass_rule_as_ccx = false;  // tet_mass_rule = "ccx"
    int shapes = -1;  // mode shapes to write; < 0 all, 0 none
    std::vector<CasePart> parts;
    std::vector<CaseSupport> supports;
    std::vector<CaseCoupling> couplings;
};

/// Parses and validates the case file (input/toml_input.hpp: every key typed and range-checked,
/// unknown or unused keys refused); InputError naming the file, line, key and problem (missing
/// file, TOML syntax, unknown material, non-physical material, unknown DOF name...).
ModalCase read_modal_case(const std::filesystem::path& path);
/// The same from case-file text; `source` names it in messages, `base` is where relative paths start.
ModalCase parse_modal_case(std::string_view text, const std::string& source, const std::filesystem::path& base = ".");

/// Reads the mesh, builds the model, solves, writes the results into case.output as one run's set
/// (io::RunFolder: the folder is checked before solving, a concurrent run into it is refused, the
/// previous run's files are replaced and listed in manifest.txt) and returns the run summary.
/// Unknown physical groups and blocks without a part are InputErrors.
std::string run_modal_case(const ModalCase& c);

/// The solid element options of a case (mass kind, tetrahedra mass rules).
SolidOptions solid_options(const ModalCase& c);
/// The model of a case on its mesh: each part's blocks with their element formulation, supports and
/// couplings (what run_modal_case solves and export_case_deck writes).
void build_case_model(const ModalCase& c, const Mesh& mesh, Model& model);

/// Writes the case's model as a CalculiX/Abaqus deck with a *FREQUENCY step of case.options.modes
/// modes, so that `ccx <stem>` checks it; returns notes on what ccx will compute differently (the
/// tet10 mass rule, MITC4 against ccx's S4).
std::string export_case_deck(const ModalCase& c, const std::filesystem::path& deck);

}  // namespace fem::modal
