// The fem-modal case file and its errors (lib/modal/case): a Gmsh-meshed tet10 cantilever (made by
// the gmsh program, in both .msh 2.2 and 4.1), solved through read_modal_case/run_modal_case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

#include "core/error.hpp"
#include "io/hdf5.hpp"
#include "modal/case.hpp"

using namespace fem;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::temp_directory_path() / "fem_test_modal_case";

// Meshes the 1 m x 50 mm x 50 mm beam once per format with physical groups "beam" and "root".
fs::path beam_mesh(const std::string& format) {
    const fs::path msh = kDir / ("beam_" + format + ".msh");
    if (fs::exists(msh)) return msh;
    fs::create_directories(kDir);
    // CTest may run two tests of this file at once: each meshes into its own file and renames it.
    const std::string tag = std::to_string(::getpid());
    const fs::path geo = kDir / ("beam_" + tag + ".geo"), partial = kDir / ("beam_" + tag + ".msh");
    std::ofstream(geo) << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1.0, 0.05, 0.05};\n"
                          "Physical Volume(\"beam\") = {1};\nPhysical Surface(\"root\") = {1};\n"
                          "Mesh.CharacteristicLengthMax = 0.025;\nMesh.ElementOrder = 2;\n";
    const std::string cmd = "gmsh -3 '" + geo.string() + "' -format " + format + " -o '" + partial.string() +
                            "' -v 0 > /dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("gmsh failed: " + cmd);
    fs::rename(partial, msh);
    fs::remove(geo);
    return msh;
}

fs::path write_case(const std::string& name, const std::string& text) {
    fs::create_directories(kDir);
    const fs::path p = kDir / name;
    std::ofstream(p) << text;
    return p;
}

std::string beam_case(const std::string& mesh, const std::string& material = "E = 210e9\nnu = 0.3\nrho = 7800.0\n",
                      const std::string& supports = "[[supports]]\nset = \"root\"\n", const std::string& part = "beam") {
    return "mesh = \"" + mesh + "\"\nmodes = 4\n[materials.steel]\n" + material + "[[parts]]\nname = \"" + part +
           "\"\nmaterial = \"steel\"\n" + supports;
}

std::string error_of(const fs::path& case_file) {
    try {
        modal::run_modal_case(modal::read_modal_case(case_file));
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(ModalCase, GmshBeamInBothFormatsMatchesEulerBernoulli) {
    // Euler-Bernoulli first bending frequency of the steel cantilever; 1 % as in test_modal (L/h = 20).
    const double f_eb = 1.8751040687 * 1.8751040687 / (2 * std::numbers::pi) * std::sqrt(210e9 * std::pow(0.05, 2) / 12 / 7800.0);
    double f1[2];
    int i = 0;
    for (const std::string format : {"msh22", "msh41"}) {
        beam_mesh(format);
        const fs::path c = write_case("beam_" + format + ".toml", beam_case("beam_" + format + ".msh"));
        const std::string summary = modal::run_modal_case(modal::read_modal_case(c));
        EXPECT_NE(summary.find("mode"), std::string::npos);
        const Eigen::MatrixXd f = io::read_h5_matrix(kDir / ("beam_" + format + "_modes") / "modes.h5", "frequencies_hz");
        ASSERT_EQ(f.size(), 4);
        EXPECT_NEAR(f(0) / f_eb, 1.0, 0.01) << format;
        f1[i++] = f(0);
    }
    EXPECT_NEAR(f1[0], f1[1], 1e-9 * f1[0]);  // the same mesh in two file formats
}

TEST(ModalCase, BadInputIsNamed) {
    beam_mesh("msh41");
    EXPECT_THROW(modal::read_modal_case(kDir / "nope.toml"), InputError);
    EXPECT_NE(error_of(write_case("missing_mesh.toml", beam_case("absent.msh"))).find("absent.msh"), std::string::npos);
    std::ofstream(kDir / "garbage.msh") << "$MeshFormat\nthis is not a mesh\n";
    EXPECT_NE(error_of(write_case("garbage.toml", beam_case("garbage.msh"))), "no error");
    EXPECT_NE(error_of(write_case("nu.toml", beam_case("beam_msh41.msh", "E = 210e9\nnu = 0.5\nrho = 7800.0\n"))).find("steel"),
              std::string::npos);
    EXPECT_NE(error_of(write_case("set.toml", beam_case("beam_msh41.msh", "E = 210e9\nnu = 0.3\nrho = 7800.0\n",
                                                        "[[supports]]\nset = \"clamp\"\n")))
                  .find("clamp"),
              std::string::npos);
    EXPECT_NE(error_of(write_case("part.toml", beam_case("beam_msh41.msh", "E = 210e9\nnu = 0.3\nrho = 7800.0\n",
                                                         "[[supports]]\nset = \"root\"\n", "girder")))
                  .find("girder"),
              std::string::npos);
    EXPECT_NE(error_of(write_case("free.toml", beam_case("beam_msh41.msh", "E = 210e9\nnu = 0.3\nrho = 7800.0\n", ""))).find(
                  "rigid-body modes: add supports or use shift"),
              std::string::npos);
    EXPECT_NE(error_of(write_case("dofs.toml", beam_case("beam_msh41.msh", "E = 210e9\nnu = 0.3\nrho = 7800.0\n",
                                                         "[[supports]]\nset = \"root\"\ndofs = [\"uq\"]\n")))
                  .find("uq"),
              std::string::npos);
}

// The element formulation per part (`element`), the tetrahedra's mass rule (`tet_mass_rule`) and the
// shapes written (`shapes`) take effect as written or are refused.
TEST(ModalCase, ElementMassRuleAndShapesKeys) {
    beam_mesh("msh41");
    const std::string base = beam_case("beam_msh41.msh");
    const auto first_frequency = [&](const std::string& name, const std::string& extra) {
        modal::run_modal_case(modal::read_modal_case(write_case(name + ".toml", extra + base)));
        return io::read_h5_matrix(kDir / (name + "_modes") / "modes.h5", "frequencies_hz")(0);
    };
    const double exact = first_frequency("rule_exact", "");
    const double ccx = first_frequency("rule_ccx", "tet_mass_rule = \"ccx\"\n");
    // ccx's 4-point C3D10 mass underintegrates N^T N: slightly different (measured ~1e-4), not equal.
    EXPECT_NE(exact, ccx);
    EXPECT_NEAR(ccx / exact, 1.0, 1e-3);
    // shapes = 1: one VTU and one translation dataset.
    first_frequency("one_shape", "shapes = 1\n");
    int vtus = 0;
    for (const auto& f : fs::directory_iterator(kDir / "one_shape_modes")) vtus += f.path().extension() == ".vtu";
    EXPECT_EQ(vtus, 1);
    io::H5Reader h5(kDir / "one_shape_modes" / "modes.h5");
    EXPECT_TRUE(h5.has("mode_1/translation"));
    EXPECT_FALSE(h5.has("mode_2/translation"));
    // Refused: a formulation that does not fit the mesh, an unknown one, more shapes than modes.
    std::string part_with = base;
    part_with.replace(part_with.find("material = \"steel\"\n"), 19, "material = \"steel\"\nelement = \"C3D8\"\n");
    EXPECT_NE(error_of(write_case("c3d8_on_tets.toml", part_with)).find("element = \"C3D8\" does not fit its tet10 elements"),
              std::string::npos)
        << error_of(write_case("c3d8_on_tets.toml", part_with));
    part_with.replace(part_with.find("C3D8"), 4, "C3D9");
    EXPECT_NE(error_of(write_case("c3d9.toml", part_with)).find("did you mean"), std::string::npos);
    EXPECT_NE(error_of(write_case("shapes.toml", "shapes = 5\n" + base)).find("shapes: must be <= modes (4), got 5"),
              std::string::npos);
    EXPECT_NE(error_of(write_case("rule.toml", "tet_mass_rule = \"four_point\"\n" + base)).find("tet_mass_rule"),
              std::string::npos);
}
