// The fem-topopt case file (topopt/case_file.hpp): a valid case, and the InputErrors a user meets.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "topopt/case_file.hpp"

using namespace fem;
using namespace fem::topopt;

namespace {

const std::string kCantilever = R"(
[domain]
type = "rectangle"
size = [0.15, 0.1]
elements = [15, 10]
element = "quad8"
thickness = 0.001

[material]
E = 207e9
nu = 0.3

[optimization]
removed = 0.7
filter_radius = 0.015
max_iterations = 3

[[support]]
edge = "x0"
fix = ["x", "y"]

[[load]]
at = [0.15, 0.05]
force = [0.0, -3000.0]

[[passive]]
kind = "void"
circle = [0.1, 0.05, 0.012]
)";

// The case text with `from` replaced by `to` (exactly once).
std::string edit(std::string text, const std::string& from, const std::string& to) {
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return text.replace(pos, from.size(), to);
}

// Expects an InputError whose message contains `needle`.
void expect_error(const std::string& text, const std::string& needle) {
    try {
        const Case c = parse_case(text, "case.toml");
        optimize(c.model, c.settings);
        ADD_FAILURE() << "accepted; expected an error mentioning '" << needle << "'";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

TEST(CaseFile, ReadsTheCantileverAndRuns) {
    const Case c = parse_case(kCantilever, "case.toml");
    EXPECT_EQ(c.model.element_count(), 150);
    EXPECT_NEAR(c.settings.volume_fraction, 0.3, 1e-15);
    EXPECT_EQ(c.model.loads.size(), 1u);
    int voids = 0;
    for (auto r : c.model.region) voids += r == Region::Void;
    EXPECT_GT(voids, 0);
    const Result r = optimize(c.model, c.settings);
    EXPECT_EQ(r.iterations, 3);
}

TEST(CaseFile, ReportsBadInput) {
    expect_error(edit(kCantilever, "removed = 0.7", "removed = 1.2"), "case.toml:14: optimization.removed: must be a finite number in (0, 1), got 1.2");
    expect_error(edit(kCantilever, "removed = 0.7", "volume_fraction = 0.0"), "optimization.volume_fraction: must be a finite number in (0, 1)");
    expect_error(edit(kCantilever, "at = [0.15, 0.05]", "at = [0.2, 0.05]"), "no node at (0.2, 0.05)");
    expect_error(edit(kCantilever, "at = [0.15, 0.05]", "box = [0.2, 0.0, 0.3, 0.1]"), "load[0]: the selection holds no node");
    expect_error(edit(kCantilever, "fix = [\"x\", \"y\"]", "fix = [\"x\"]"), "singular");
    expect_error(edit(kCantilever, "nu = 0.3", "nu = 0.5"), "material.nu: must be a finite number in (-1, 0.5), got 0.5");
    expect_error(edit(kCantilever, "thickness = 0.001", "thickness = 0.001\ncolour = 3"), "unknown key 'colour'");
    expect_error(edit(kCantilever, "edge = \"x0\"", "edge = \"left\""), "support[0].edge: 'left' is not x0, x1, y0 or y1");
    expect_error(edit(kCantilever, "filter_radius = 0.015", "filter_radius = -1.0"), "filter_radius: must be a finite number > 0");
    expect_error(edit(kCantilever, "kind = \"void\"", "kind = \"air\""), "passive[0].kind: 'air' is not void or solid");
    expect_error(edit(kCantilever, "force = [0.0, -3000.0]", "force = [0.0, -3000.0]\ncase = 2"), "load case 2 cannot exist");
    expect_error(edit(kCantilever, "max_iterations = 3", "max_iterations = 2.7"), "max_iterations: must be an integer >= 1, got 2.7");
    expect_error(edit(kCantilever, "filter_radius = 0.015", "filter_radus = 0.015"), "unknown key 'filter_radus' (did you mean 'filter_radius'?)");
    expect_error("[domain\n", "case.toml:");
    EXPECT_THROW(read_case("/nonexistent/case.toml"), InputError);
}

}  // namespace

namespace {

TEST(CaseFile, ReadsAGmshMeshWithNamedNodeSets) {
    // Two quad4 elements (physical surface "plate") and the left edge as physical curve "left".
    const auto dir = std::filesystem::temp_directory_path() / "fem_topopt_case_test";
    std::filesystem::create_directories(dir);
    {
        std::ofstream msh(dir / "plate.msh");
        msh << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
               "$PhysicalNames\n2\n1 2 \"left\"\n2 1 \"plate\"\n$EndPhysicalNames\n"
               "$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2 1 0\n$EndNodes\n"
               "$Elements\n3\n1 1 2 2 1 1 4\n2 3 2 1 1 1 2 5 4\n3 3 2 1 1 2 3 6 5\n$EndElements\n";
    }
    const std::string text = R"(
[domain]
type = "gmsh"
mesh = "plate.msh"
thickness = 0.01
[material]
E = 1e9
nu = 0.3
[optimization]
volume_fraction = 0.5
filter = "none"
max_iterations = 2
[[support]]
node_set = "left"
fix = ["x", "y"]
[[load]]
at = [2.0, 1.0]
force = [0.0, -1.0]
)";
    const Case c = parse_case(text, "gmsh-case.toml", dir);
    EXPECT_EQ(c.model.element_count(), 2);
    EXPECT_EQ(c.mesh.node_count(), 6);
    const Result r = optimize(c.model, c.settings);
    EXPECT_EQ(r.iterations, 2);
    try {
        parse_case(std::string(text).replace(text.find("\"left\""), 6, "\"right\""), "gmsh-case.toml", dir);
        ADD_FAILURE() << "an unknown node set was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("node set 'right' is not in the mesh"), std::string::npos) << e.what();
    }
}

}  // namespace
