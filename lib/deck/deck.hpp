#pragma once
// Abaqus / CalculiX input decks (the keyword format both programs read): a reader for the subset
// that describes a linear model and a frequency step, and a writer of the same subset, so that our
// models can be run by ccx in one command (`fem-modal case.toml --export-deck model.inp`).
//
// Keywords read (case-insensitive; `**` starts a comment; a keyword line ending in a comma continues
// on the next line; data lines of an element continue while nodes are missing):
//
//   *NODE [, NSET=n]                     id, x, y, z
//   *ELEMENT, TYPE=t [, ELSET=e]         id, node ...   t: C3D4 C3D10 C3D8 C3D8I C3D20 C3D20R S4 S4R
//   *NSET, NSET=n [, GENERATE]           ids or set names; GENERATE: first, last[, step]
//   *ELSET, ELSET=e [, GENERATE]         the same for elements
//   *INCLUDE, INPUT=file                 relative to the including file
//   *MATERIAL, NAME=m / *ELASTIC [, TYPE=ISO] (E, nu) / *DENSITY (rho)
//   *SOLID SECTION, ELSET=e, MATERIAL=m
//   *SHELL SECTION, ELSET=e, MATERIAL=m  thickness
//   *BOUNDARY                            node or set, first DOF[, last DOF[, 0]]
//   *EQUATION                            2 / node a, dof, c, node b, dof, -c: u_a = u_b (coupled DOFs,
//                                        the screws of thesis Table 2-5)
//   *STEP [, PERTURBATION] / *FREQUENCY [, STORAGE=...] (number of modes) / *END STEP
//   *HEADING, *NODE FILE, *EL FILE, *NODE PRINT, *EL PRINT, *NODE OUTPUT, *ELEMENT OUTPUT, *OUTPUT:
//                                        read and listed in Deck::notes as not acted upon
//
// Anything else is refused with the file, the line and the culprit: an unknown keyword or parameter
// (with "did you mean"), an element type we do not have, a node or set that does not exist, a
// number that is not one (through input/numbers.hpp), a general *EQUATION, a non-zero prescribed
// displacement, an element in no section or in two.
//
// Element formulations follow the deck type so results compare with ccx element for element (see
// modal::add_element_block()): C3D8 the fully integrated trilinear brick, C3D8I the incompatible-modes
// brick with its bubble amplitudes as element DOFs that carry mass (as ccx), C3D10 with ccx's 4-point
// mass rule, S4/S4R our MITC4 shell (ccx expands shells into
// C3D8I bricks: a different formulation, see tests/deck/peer_ccx_decks.cpp).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "material/elastic.hpp"
#include "mesh/mesh.hpp"

namespace fem::deck {

/// What an element block of a deck is made of: the deck type name, its shape in the library and its
/// section (material, shell thickness).
struct Section {
    enum Kind { Solid, Shell } kind = Solid;
    std::string elset;     // the element set it applies to (upper case)
    std::string material;  // upper case, a key of Deck::materials
    double thickness = 0;  // shells
};

/// *BOUNDARY line: DOFs first..last (1..6: ux uy uz rx ry rz) of a node fixed.
struct Boundary {
    int node = 0;  // mesh node index
    int first = 1, last = 1;
};

/// *EQUATION u_a(dof) - u_b(dof) = 0: coupled DOFs.
struct Equation {
    int node_a = 0, node_b = 0;  // mesh node indices
    int dof = 1;                 // 1..6
};

struct Frequency {
    int modes = 10;
};

struct Deck {
    std::filesystem::path file;
    /// Nodes in deck order; one block per (element type, section), part = the section's element set,
    /// the deck's element numbers as the block's ids (write_deck numbers a block without ids after
    /// the largest); node sets under their upper-case deck names.
    Mesh mesh;
    std::vector<int> node_ids;                  // deck number of each mesh node
    std::vector<std::string> block_types;       // deck element type of each block ("C3D8I")
    std::vector<int> block_section;             // index into sections
    std::map<std::string, ElasticMaterial> materials;
    std::vector<Section> sections;
    std::vector<Boundary> boundaries;
    std::vector<Equation> equations;
    std::optional<Frequency> frequency;
    /// Keywords read but not acted upon, with their place ("model.inp:31: *NODE FILE (output request;
    /// fem-modal writes modes.h5 and VTU files instead)").
    std::vector<std::string> notes;
};

/// The deck element types we read, in the order messages list them.
const std::vector<std::string>& supported_element_types();
/// The library's shape of a supported deck element type (C3D8I -> Hex8).
ElementShape shape_of_type(std::string_view type);

/// Reads a deck (and its *INCLUDEs); InputError "file:line: culprit: problem" for anything it
/// cannot honour.
Deck read_deck(const std::filesystem::path& path);
/// The same from text; `source` names it in messages, `base` is where *INCLUDE paths start.
Deck parse_deck(std::string_view text, const std::string& source, const std::filesystem::path& base = ".");

/// Writes the deck (nodes, elements per block, element sets, materials, sections, boundaries,
/// equations, the frequency step) so that ccx and read_deck run it. Atomic (io::AtomicFile).
void write_deck(const std::filesystem::path& path, const Deck& deck, std::string_view heading = "fem deck");

}  // namespace fem::deck
