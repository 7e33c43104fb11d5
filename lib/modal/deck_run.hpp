#pragma once
// CalculiX / Abaqus decks in fem-modal: the element formulation of each deck element type, a deck's
// model, a frequency run of a deck as ccx runs it (`fem-modal model.inp`) with the eigenvalue table
// in the layout of ccx's .dat file, and the conversion of our own models into decks.
//
// Element types and the formulation each gets (chosen so results compare with ccx element for
// element; the peer tests in tests/deck measure the agreement):
//
//   C3D4    tet4, constant strain; consistent mass with the stiffness's one point, as ccx
//           (Tet4MassRule::Centroid; a case file gets the exact mass unless it asks for ccx's rule)
//   C3D10   tet10, 4-point stiffness rule; consistent mass with the same 4-point rule, as ccx
//           (Tet10MassRule::FourPoint; likewise)
//   C3D8    hex8, fully integrated trilinear brick (2x2x2 Gauss): the same element as ccx's
//   C3D8I   hex8 with incompatible modes as ccx builds it: Wilson-Taylor's nine bubble modes (with
//           Taylor's centre-Jacobian correction) kept as nine DOFs of each element (ccx: three extra
//           nodes) that carry mass, the mass of the whole field with the 2x2x2 rule
//           (solid::hex8_incompatible_dofs; ccx's shape8humass.f). The library's brick with the
//           bubbles condensed (what the studies use, SolidOptions::incompatible_modes) has the same
//           stiffness and no bubble mass: on the peer test's 10 x 2 x 3 brick it is up to 3.6 % off
//           ccx, this one identical to ccx's 7 digits (tests/deck/peer_ccx_decks.cpp). With a lumped
//           mass (case files) the bubbles carry none, which is exactly the condensed brick.
//           The price of ccx's way: 9 more equations per element (a clamped 80 x 8 x 8 brick: 65,520
//           equations instead of 19,440, 2-3 times the solve time).
//   C3D20   hex20 serendipity brick, 3x3x3 Gauss for stiffness and mass
//   C3D20R  the same with 2x2x2 Gauss for both, as ccx
//   S4, S4R MITC4 shell, 6 DOF per node (ccx expands shells into C3D8I bricks: a different
//           formulation; both converge to the same plate answer)
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "assembly/model.hpp"
#include "deck/deck.hpp"
#include "modal/modal.hpp"

namespace fem::modal {

/// Adds block `block` of `model` as elements of deck type `type` (table above) of material m;
/// `thickness` for shells. `options.mass` and the tet mass rules apply where the type has a choice.
void add_element_block(Model& model, int block, std::string_view type, const ElasticMaterial& m, double thickness,
                       const SolidOptions& options);
/// DOFs per node of a deck type: 6 for shells, 3 for solids.
int dofs_per_node(std::string_view type);
/// The deck types that fit a mesh shape (for case files: hex8 -> C3D8I, C3D8; the first is the default).
std::vector<std::string> element_types_for(ElementShape shape);

/// Adds the deck's blocks, *BOUNDARY and *EQUATION to `model` (whose mesh is deck.mesh).
void build_deck_model(const deck::Deck& deck, Model& model);

/// The eigenvalue table as ccx prints it in <job>.dat ("E I G E N V A L U E   O U T P U T": mode,
/// eigenvalue, omega [rad/time], frequency [cycles/time], imaginary part), so a user's scripts that
/// read ccx's .dat read ours.
std::string ccx_eigenvalue_table(const ModalResult& result);

struct DeckRunOptions {
    std::filesystem::path output;  // default: <deck folder>/<deck stem>_modes
    int modes = 0;                 // 0: the deck's *FREQUENCY count
    int shapes = -1;               // mode shapes written; < 0 all, 0 none
};

/// Runs the frequency step of a deck: reads it, builds the model, solves with rigid-body modes
/// admitted (ModalOptions::admit_rigid_body_modes, as ccx solves a free model), writes
/// frequencies.csv, modes.h5, the shapes asked for and <deck stem>.dat (the eigenvalue table) into
/// the output folder (io::RunFolder) and returns the table followed by notes on keywords not acted
/// upon. InputError for a deck without *FREQUENCY.
std::string run_deck(const std::filesystem::path& deck, const DeckRunOptions& options = {});

}  // namespace fem::modal
