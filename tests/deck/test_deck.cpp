// The Abaqus/CalculiX deck reader and writer (lib/deck), the deck run of fem-modal (lib/modal/
// deck_run) and its output choices, and the tet4 element the decks brought (C3D4).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli/programs.hpp"
#include "core/error.hpp"
#include "deck/deck.hpp"
#include "element/solid_elements.hpp"
#include "io/hdf5.hpp"
#include "mesh/mesh.hpp"
#include "modal/deck_run.hpp"

using namespace fem;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::temp_directory_path() / "fem_test_deck";

// One C3D10 element (its line continued), one C3D8 brick beside it, sets, an include, a coupling.
const char* kDeck = R"(** a comment
*Heading
 reader test
*node, nset=Nall
1, 0, 0, 0
2, 1, 0, 0
3, 0, 1, 0
4, 0, 0, 1
5, 0.5, 0, 0
6, 0.5, 0.5, 0
7, 0, 0.5, 0
8, 0, 0, 0.5
9, 0.5, 0, 0.5
10, 0, 0.5, 0.5
*INCLUDE, INPUT=brick_nodes.inc
*ELEMENT, TYPE=C3D10,
  ELSET=TET
1, 1, 2, 3, 4, 5, 6, 7, 8,
9, 10
*Element, type=c3d8, elset=BRICK
2, 11, 12, 13, 14, 15, 16, 17, 18
*NSET, NSET=BASE, GENERATE
11, 14
*NSET, NSET=CORNERS
1, 2, BASE
*ELSET, ELSET=ALL
TET, BRICK
*MATERIAL, NAME=Steel
*ELASTIC
210e9, 0.3
*DENSITY
7800.
*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL
*BOUNDARY
BASE, 1, 3
1, 1
*EQUATION
2
4, 2, 1., 18, 2, -1.
*STEP
*FREQUENCY
12
*NODE FILE
U
*END STEP
)";

const char* kBrickNodes = R"(** the brick, x from 2 to 3
11, 2, 0, 0
12, 3, 0, 0
13, 3, 1, 0
14, 2, 1, 0
15, 2, 0, 1
16, 3, 0, 1
17, 3, 1, 1
18, 2, 1, 1
)";

fs::path write(const std::string& name, const std::string& text) {
    fs::create_directories(kDir);
    std::ofstream(kDir / name) << text;
    return kDir / name;
}

deck::Deck parse(const std::string& text) {
    write("brick_nodes.inc", kBrickNodes);
    return deck::parse_deck(text, (kDir / "model.inp").string(), kDir);
}

// The error message of parsing `text`.
std::string error_of(const std::string& text) {
    try {
        parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

// kDeck with `from` replaced by `to` (exactly once).
std::string edited(const std::string& from, const std::string& to) {
    std::string s = kDeck;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
}

}  // namespace

TEST(Deck, ReadsEveryKeyword) {
    const deck::Deck d = parse(kDeck);
    ASSERT_EQ(d.mesh.node_count(), 18);
    EXPECT_EQ(d.node_ids[10], 11);
    EXPECT_DOUBLE_EQ(d.mesh.nodes[11].x(), 3.0);  // from the included file
    ASSERT_EQ(d.mesh.blocks.size(), 2u);
    EXPECT_EQ(d.block_types[0], "C3D10");
    EXPECT_EQ(d.block_types[1], "C3D8");
    EXPECT_EQ(d.mesh.blocks[0].part, "ALL");
    // C3D10's mid-edge nodes 13 and 23 (deck nodes 9, 10) come out in the library's order 23, 13.
    const auto tet = d.mesh.blocks[0].element(0);
    EXPECT_EQ(d.node_ids[tet[8]], 10);
    EXPECT_EQ(d.node_ids[tet[9]], 9);
    EXPECT_EQ(d.mesh.blocks[1].ids, std::vector<long>{2});
    EXPECT_EQ(d.mesh.blocks[1].id(0), 2);  // the deck's number, not the position in the block
    EXPECT_EQ(d.mesh.node_set("BASE"), (std::vector<int>{10, 11, 12, 13}));
    EXPECT_EQ(d.mesh.node_set("CORNERS").size(), 6u);  // 1, 2 and the set BASE
    EXPECT_EQ(d.mesh.node_set("NALL").size(), 18u);  // the *INCLUDE inside the *NODE data continues it
    ASSERT_EQ(d.materials.count("STEEL"), 1u);
    EXPECT_DOUBLE_EQ(d.materials.at("STEEL").density, 7800.0);
    ASSERT_EQ(d.boundaries.size(), 5u);
    EXPECT_EQ(d.boundaries[4].node, 0);
    EXPECT_EQ(d.boundaries[4].first, 1);
    EXPECT_EQ(d.boundaries[4].last, 1);
    ASSERT_EQ(d.equations.size(), 1u);
    EXPECT_EQ(d.equations[0].node_a, 3);
    EXPECT_EQ(d.equations[0].node_b, 17);
    EXPECT_EQ(d.equations[0].dof, 2);
    ASSERT_TRUE(d.frequency);
    EXPECT_EQ(d.frequency->modes, 12);
    ASSERT_EQ(d.notes.size(), 1u);
    EXPECT_NE(d.notes[0].find("model.inp:43: *NODE FILE"), std::string::npos) << d.notes[0];
}

TEST(Deck, WrittenDeckReadsBackTheSame) {
    const deck::Deck d = parse(kDeck);
    deck::write_deck(kDir / "round.inp", d);
    const deck::Deck e = deck::read_deck(kDir / "round.inp");
    ASSERT_EQ(e.mesh.node_count(), d.mesh.node_count());
    for (int i = 0; i < d.mesh.node_count(); ++i) EXPECT_EQ(e.mesh.nodes[i], d.mesh.nodes[i]);
    ASSERT_EQ(e.mesh.blocks.size(), d.mesh.blocks.size());
    for (std::size_t b = 0; b < d.mesh.blocks.size(); ++b) {
        EXPECT_EQ(e.mesh.blocks[b].connectivity, d.mesh.blocks[b].connectivity);
        EXPECT_EQ(e.block_types[b], d.block_types[b]);
    }
    EXPECT_EQ(e.boundaries.size(), d.boundaries.size());
    EXPECT_EQ(e.equations.size(), d.equations.size());
    EXPECT_EQ(e.frequency->modes, 12);
}

TEST(Deck, BadInputIsNamedWithFileAndLine) {
    // Element types: one we do not have, and the 20-node brick that is not there yet.
    auto e = error_of(edited("type=c3d8,", "type=C3D6,"));
    EXPECT_NE(e.find("model.inp:20"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown element type 'C3D6'"), std::string::npos) << e;
    e = error_of(edited("type=c3d8,", "type=C3D20,"));  // a C3D20 needs 20 nodes
    EXPECT_NE(e.find("model.inp:21: *ELEMENT, TYPE=C3D20: an element needs its number and 20 nodes, got 9 fields"),
              std::string::npos) << e;
    // Keywords and parameters, with "did you mean".
    e = error_of(edited("*FREQUENCY\n", "*FREQUENCE\n"));
    EXPECT_NE(e.find("model.inp:41: unsupported keyword '*FREQUENCE' (did you mean '*FREQUENCY'?)"), std::string::npos) << e;
    e = error_of(edited("*NSET, NSET=CORNERS", "*NSET, NSTE=CORNERS"));
    EXPECT_NE(e.find("unknown parameter 'NSTE'"), std::string::npos) << e;
    // Numbers through input/numbers.hpp.
    e = error_of(edited("210e9, 0.3", "210e9, 0.3x"));
    EXPECT_NE(e.find("model.inp:30: *ELASTIC, field 2 (nu)"), std::string::npos) << e;
    e = error_of(edited("210e9, 0.3", "210e9, 0.5"));
    EXPECT_NE(e.find("*ELASTIC, field 2 (nu): must be a finite number in (-1, 0.5)"), std::string::npos) << e;
    e = error_of(edited("12\n*NODE FILE", "0\n*NODE FILE"));
    EXPECT_NE(e.find("number of modes"), std::string::npos) << e;
    // References that do not resolve.
    e = error_of(edited("2, 11, 12,", "2, 99, 12,"));
    EXPECT_NE(e.find("model.inp:21: *ELEMENT 2, node 1: node 99 is not defined"), std::string::npos) << e;
    e = error_of(edited("BASE, 1, 3", "BSAE, 1, 3"));
    EXPECT_NE(e.find("node set 'BSAE' is not defined (did you mean 'BASE'?)"), std::string::npos) << e;
    e = error_of(edited("ELSET=ALL, MATERIAL", "ELSET=TET, MATERIAL"));
    EXPECT_NE(e.find("element 2 (C3D8) is in no *SOLID SECTION"), std::string::npos) << e;
    e = error_of(edited("*DENSITY\n7800.\n", ""));
    EXPECT_NE(e.find("has no *DENSITY"), std::string::npos) << e;
    e = error_of(edited("1, 0, 0, 0\n", "1, 0, 0, 0\n1, 1, 1, 1\n"));
    EXPECT_NE(e.find("node 1 is defined twice"), std::string::npos) << e;
    // What the model cannot honour.
    e = error_of(edited("2\n4, 2, 1., 18, 2, -1.", "2\n4, 2, 1., 18, 2, -2."));
    EXPECT_NE(e.find("only equal DOFs with opposite coefficients"), std::string::npos) << e;
    e = error_of(edited("2\n4, 2, 1., 18, 2, -1.", "3\n4, 2, 1., 18, 2, -1., 17, 2, 1."));
    EXPECT_NE(e.find("*EQUATION with 3 terms"), std::string::npos) << e;
    e = error_of(edited("1, 1\n", "1, 1, 1, 0.001\n"));
    EXPECT_NE(e.find("*BOUNDARY, field 4 (value): a prescribed displacement"), std::string::npos) << e;
    e = error_of(edited("*INCLUDE, INPUT=brick_nodes.inc", "*INCLUDE, INPUT=absent.inc"));
    EXPECT_NE(e.find("cannot open"), std::string::npos) << e;
    e = error_of(edited("U\n*END STEP\n", "U\n"));
    EXPECT_NE(e.find("*STEP without *END STEP"), std::string::npos) << e;
    // A deck without a frequency step is refused by fem-modal (the reader takes it).
    const fs::path no_step = write("nostep.inp", edited("*STEP\n*FREQUENCY\n12\n*NODE FILE\nU\n*END STEP\n", ""));
    write("brick_nodes.inc", kBrickNodes);
    try {
        modal::run_deck(no_step, {.output = kDir / "nostep_out"});
        ADD_FAILURE() << "no error";
    } catch (const InputError& x) {
        EXPECT_NE(std::string(x.what()).find("has no *STEP with *FREQUENCY"), std::string::npos) << x.what();
    }
}

TEST(Deck, EigenvalueTableHasCcxLayout) {
    modal::ModalResult r;
    r.eigenvalues.resize(2);
    r.eigenvalues << 0.1395836e8, -2.161314e-6;
    const std::string t = modal::ccx_eigenvalue_table(r);
    // ccx 2.20 .dat lines (a free C3D8 brick): mode, eigenvalue, omega, cycles/time, imaginary part.
    EXPECT_NE(t.find("     E I G E N V A L U E   O U T P U T\n"), std::string::npos) << t;
    EXPECT_NE(t.find("\n      1   0.1395836E+08   0.3736089E+04   0.5946170E+03   0.0000000E+00\n"), std::string::npos) << t;
    EXPECT_NE(t.find("\n      2  -0.2161314E-05   0.0000000E+00   0.0000000E+00   0.1470141E-02\n"), std::string::npos) << t;
}

// fem-modal model.inp: the eigenvalue table on stdout and in <stem>.dat; --shapes picks the VTUs.
TEST(Deck, FemModalRunsADeckAndWritesTheShapesAsked) {
    // A clamped C3D8 cantilever written by write_deck. (Not kDeck: its lone tetrahedron has ccx's
    // 4-point mass, of rank 4 per component, so M alone is singular.)
    deck::Deck d;
    d.mesh = box_hex8(0.4, 0.05, 0.08, 6, 1, 2, "EALL");
    d.block_types = {"C3D8"};
    d.block_section = {0};
    d.materials.emplace("STEEL", ElasticMaterial::make("STEEL", 210e9, 0.3, 7800.0));
    d.sections.push_back({deck::Section::Solid, "EALL", "STEEL", 0});
    for (int n : d.mesh.node_set("x0")) d.boundaries.push_back({n, 1, 3});
    d.frequency = deck::Frequency{5};
    fs::create_directories(kDir);
    deck::write_deck(kDir / "beam.inp", d);
    const std::string m = (kDir / "beam.inp").string();
    for (const auto& [shapes, vtus] : {std::pair{"0", 0}, {"2", 2}, {"", 5}}) {
        const std::string out = (kDir / (std::string("out_") + shapes)).string();
        std::vector<const char*> argv = {"fem-modal", m.c_str(), "--output", out.c_str()};
        if (*shapes) argv.insert(argv.end(), {"--shapes", shapes});
        ASSERT_EQ(cli::modal_program(static_cast<int>(argv.size()), const_cast<char**>(argv.data())), 0);
        EXPECT_TRUE(fs::exists(fs::path(out) / "beam.dat"));
        EXPECT_TRUE(fs::exists(fs::path(out) / "frequencies.csv"));
        EXPECT_EQ(fs::exists(fs::path(out) / "modes.pvd"), vtus > 0);
        int count = 0;
        for (const auto& f : fs::directory_iterator(out)) count += f.path().extension() == ".vtu";
        EXPECT_EQ(count, vtus) << "--shapes " << shapes;
        io::H5Reader h5(fs::path(out) / "modes.h5");
        EXPECT_EQ(h5.read("frequencies_hz").size(), 5u);
        EXPECT_EQ(h5.has("mode_1/translation"), vtus > 0);
        EXPECT_EQ(h5.has("mode_3/translation"), vtus > 2);
        EXPECT_EQ(h5.attribute_number("/", "shapes_written"), vtus);
    }
    const std::string out = (kDir / "out_bad").string();
    const char* too_many[] = {"fem-modal", m.c_str(), "--output", out.c_str(), "--shapes", "6"};
    EXPECT_EQ(cli::modal_program(6, const_cast<char**>(too_many)), 2);
}

// C3D4: the constant-strain tetrahedron reproduces a linear displacement field exactly (patch test
// on one element: K u = 0 for rigid motions, strain energy of a uniform strain), both mass rules
// carry the element mass.
TEST(Tet4, RigidMotionsUniformStrainAndMass) {
    const std::vector<Vec3> x = {{0.1, 0, 0}, {1.2, 0.1, 0}, {0.2, 0.9, 0.1}, {0.3, 0.2, 1.1}};
    const auto steel = ElasticMaterial::make("steel", 210e9, 0.3, 7800.0);
    const Eigen::MatrixXd K = solid::tet4_stiffness(x, steel);
    const double volume = (x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]) / 6;
    Eigen::VectorXd u(12);
    for (int a = 0; a < 4; ++a) u.segment<3>(3 * a) = Vec3(0.01, -0.02, 0.03) + Vec3(0.1, 0.2, 0.3).cross(x[a]);
    EXPECT_LT((K * u).norm(), 1e-6 * K.norm() * u.norm());
    // u = eps_xx x: energy V E (1 - nu) / ((1 + nu)(1 - 2 nu)) eps^2 / 2.
    for (int a = 0; a < 4; ++a) u.segment<3>(3 * a) = Vec3(1e-3 * x[a].x(), 0, 0);
    const double c11 = steel.youngs_modulus * 0.7 / (1.3 * 0.4);
    EXPECT_NEAR(0.5 * u.dot(K * u), 0.5 * volume * c11 * 1e-6, 1e-9 * volume * c11 * 1e-6);
    for (auto rule : {solid::Tet4MassRule::Exact, solid::Tet4MassRule::Centroid}) {
        const Eigen::MatrixXd M = solid::tet4_mass(x, 7800.0, solid::MassKind::Consistent, rule);
        EXPECT_NEAR(M.sum() / 3, 7800.0 * volume, 1e-9 * 7800.0 * volume);
    }
    EXPECT_NEAR(solid::tet4_mass(x, 7800.0, solid::MassKind::Lumped).trace() / 3, 7800.0 * volume, 1e-9 * 7800 * volume);
}
