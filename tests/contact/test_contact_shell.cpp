// Contact with shell thickness (contact/surface.hpp): two-sided shell segments whose contact
// surfaces are offset by half the thickness, the side a node approaches from kept while the contact
// lasts, and the shell slave nodes' own offset; checked on single evaluations against the closed
// gap and force, and with the explicit solver: shell plates settling under gravity on a solid block
// and on another shell, at the distances the thicknesses set.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "core/error.hpp"

#include "../explicit/explicit_test_support.hpp"
#include "contact/contact.hpp"
#include "contact/explicit_contact.hpp"
#include "io/hdf5.hpp"

using namespace fem;
using fem::test::kShellSteel;
using namespace fem::contact;
using fem::test::quiet;

namespace {

// A 2 x 2 shell plate 0.1 x 0.1 at z = 0 (part "plate", normal +z) and a one-element probe plate
// 0.02 x 0.02 (part "probe") centred over it at height z.
Mesh plate_and_probe(double z) {
    Mesh m = rectangle_quads(0.1, 0.1, 2, 2, ElementShape::Quad4, "plate");
    Mesh probe = rectangle_quads(0.02, 0.02, 1, 1, ElementShape::Quad4, "probe");
    probe.translate(Vec3(0.04, 0.04, z));
    m.append(probe);
    return m;
}

// Net contact force on the probe's nodes for the probe at height z (and, when z_before is given,
// first at z_before, then moved to z: the contact history), master plate of thickness t_plate,
// probe of thickness t_probe.
Vec3 probe_force(double z, double t_plate, double t_probe, double z_before = NAN) {
    const Mesh m0 = plate_and_probe(std::isnan(z_before) ? z : z_before);
    ContactInterface ci("probe on plate", ContactSurface::from_part(m0, "probe", kShellSteel, 1.0, t_probe),
                        ContactSurface::from_part(m0, "plate", kShellSteel, 1.0, t_plate));
    std::vector<Vec3> x = m0.nodes, f(x.size(), Vec3::Zero());
    ci.evaluate(x, {}, 0.0, 0.0, f);
    if (!std::isnan(z_before)) {
        for (int i = 9; i < 13; ++i) x[i].z() = z;  // the probe's nodes follow the plate's 9
        std::fill(f.begin(), f.end(), Vec3::Zero());
        ci.evaluate(x, {}, 1e-6, 1e-6, f);
    }
    Vec3 sum = Vec3::Zero();
    for (int i = 9; i < 13; ++i) sum += f[i];
    return sum;
}
}  // namespace

TEST(ContactShellThickness, SurfaceCarriesOffsetsAndSides) {
    const Mesh m = plate_and_probe(0.001);
    const ContactSurface thick = ContactSurface::from_part(m, "plate", kShellSteel, 1.0, 4e-3);
    for (const auto& s : thick.segments) {
        EXPECT_TRUE(s.two_sided);
        EXPECT_DOUBLE_EQ(s.offset, 2e-3);
    }
    ASSERT_EQ(thick.node_offset.size(), thick.nodes.size());
    for (double o : thick.node_offset) EXPECT_DOUBLE_EQ(o, 2e-3);
    const ContactSurface thin = ContactSurface::from_part(m, "plate", kShellSteel);
    for (const auto& s : thin.segments) EXPECT_FALSE(s.two_sided);
    EXPECT_THROW(ContactSurface::from_part(m, "plate", kShellSteel, 1.0, -1e-3), InputError);
}

// The probe's nodes (no thickness) against a 4 mm plate: 1 mm above the mid-surface they are 1 mm
// inside the upper contact surface and pushed up with k g (k = SLSFAC 0.1 x the smaller Eq 2-30
// stiffness, here the probe's); 1 mm below it, pushed down (two-sided); 3 mm above, free. A probe
// that came from above and was pushed past the mid-surface (to -0.5 mm) is still pushed up, by its
// full 2.5 mm penetration of the upper surface. A 2 mm thick probe at 2.5 mm touches the plate's
// upper surface with its own lower one, 0.5 mm deep. Without thickness the plate is one-sided at its
// mid-surface (the earlier behaviour): a node 1 mm above is free, 1 mm below is pushed up.
TEST(ContactShellThickness, GapsFromTheOffsetSurfacesOnTheApproachSide) {
    const Mesh m = plate_and_probe(0.0);
    const ContactSurface probe = ContactSurface::from_part(m, "probe", kShellSteel);
    const double k = 0.1 * probe.node_stiffness[0];  // the probe's corner k is the smaller one
    for (double kk : probe.node_stiffness) EXPECT_DOUBLE_EQ(kk, probe.node_stiffness[0]);
    const double tol = 1e-9 * k * 1e-3;
    auto expect = [&](const Vec3& f, double fz, const char* what) {
        EXPECT_NEAR(f.x(), 0.0, tol) << what;
        EXPECT_NEAR(f.y(), 0.0, tol) << what;
        EXPECT_NEAR(f.z(), fz, tol + 1e-9 * std::abs(fz)) << what;
    };
    expect(probe_force(1e-3, 4e-3, 0.0), 4 * k * 1e-3, "1 mm above a 4 mm plate");
    expect(probe_force(-1e-3, 4e-3, 0.0), -4 * k * 1e-3, "1 mm below a 4 mm plate");
    expect(probe_force(3e-3, 4e-3, 0.0), 0.0, "3 mm above a 4 mm plate");
    expect(probe_force(-0.5e-3, 4e-3, 0.0, 1e-3), 4 * k * 2.5e-3, "pushed past the mid-surface from above");
    expect(probe_force(-0.5e-3, 4e-3, 0.0), -4 * k * 1.5e-3, "the same place approached from below");
    const ContactSurface thick_probe = ContactSurface::from_part(m, "probe", kShellSteel, 1.0, 2e-3);
    expect(probe_force(2.5e-3, 4e-3, 2e-3), 4 * 0.1 * thick_probe.node_stiffness[0] * 0.5e-3, "2 mm probe at 2.5 mm");
    expect(probe_force(1e-3, 0.0, 0.0), 0.0, "1 mm above, no thickness");
    expect(probe_force(-1e-3, 0.0, 0.0), 4 * k * 1e-3, "1 mm below, no thickness (one-sided)");
}

// The side a node touches a two-sided face from is restart state: the probe of the test above,
// 1 mm above a 4 mm plate (in contact from above), saved, restored into a fresh interface and pushed
// to 0.5 mm below the mid-surface, is pushed up by its 2.5 mm penetration of the upper surface, to the
// bit as the interface that was not interrupted; a fresh interface (no history) pushes it down. A file
// without the sides is refused while a node is in contact with a two-sided face.
TEST(ContactShellThickness, TheSideOfAShellContactIsRestartState) {
    const Mesh m = plate_and_probe(1e-3);
    auto interface = [&] {
        return ContactInterface("probe on plate", ContactSurface::from_part(m, "probe", kShellSteel),
                                ContactSurface::from_part(m, "plate", kShellSteel, 1.0, 4e-3));
    };
    std::vector<Vec3> above = m.nodes, below = m.nodes;
    for (int i = 9; i < 13; ++i) below[i].z() = -0.5e-3;
    auto push = [&](ContactInterface& ci, const std::vector<Vec3>& x, double t) {
        std::vector<Vec3> f(x.size(), Vec3::Zero());
        ci.evaluate(x, {}, t, 1e-6, f);
        return f;
    };
    ContactInterface whole = interface();
    push(whole, above, 0.0);
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "fem_contact_shell_side.h5";
    {
        io::H5Writer w(file);
        whole.save_state(w, "contact/");
        w.commit();
    }
    const std::vector<Vec3> f_whole = push(whole, below, 1e-6);
    ContactInterface restored = interface(), fresh = interface();
    restored.restore_state(io::H5Reader(file), "contact/");
    const std::vector<Vec3> f_restored = push(restored, below, 1e-6), f_fresh = push(fresh, below, 1e-6);
    for (int i = 9; i < 13; ++i) {
        EXPECT_EQ(f_restored[i], f_whole[i]) << "node " << i;
        EXPECT_GT(f_whole[i].z(), 0.0);
        EXPECT_LT(f_fresh[i].z(), 0.0);
    }
    // The file of the state above without the sides (as written before they were saved).
    const std::filesystem::path old_file = std::filesystem::temp_directory_path() / "fem_contact_shell_side_old.h5";
    {
        const io::H5Reader r(file);
        io::H5Writer w(old_file);
        for (const char* name : {"scalars", "master_resultant", "points", "pass0/friction_force"}) w.write(std::string("contact/") + name, r.read_matrix(std::string("contact/") + name));
        w.write_ints("contact/pass0/segment", r.read_ints("contact/pass0/segment"));
        w.commit();
    }
    ContactInterface from_old = interface();
    EXPECT_THROW(from_old.restore_state(io::H5Reader(old_file), "contact/"), InputError);
    std::filesystem::remove(file);
    std::filesystem::remove(old_file);
}

namespace {
// A shell plate (part "plate", 60 x 60 mm, 4 x 4 elements, thickness t) released at height z0 over
// `base` (fixed), 0.1 mm above its contact distance, under a strong gravity (1000 m/s^2) with mass
// damping (3000 1/s: terminal speed 0.33 m/s, the contact reached in 0.3 ms, settled by 6 ms): its
// mid-surface height at rest.
double rest_height(Mesh mesh, double t, double z0, const std::function<void(ExplicitModel&, const Mesh&)>& add_base,
                   const std::function<ContactSurface(const Mesh&)>& base_surface) {
    Mesh plate = rectangle_quads(0.06, 0.06, 4, 4, ElementShape::Quad4, "plate");
    plate.translate(Vec3(0.02, 0.02, z0));
    const int first = mesh.node_count();
    mesh.append(plate);
    ExplicitModel model(mesh);
    add_base(model, mesh);
    model.add_shells("plate", kShellSteel, {.thickness = t});
    model.set_gravity(Vec3(0, 0, -1000.0));
    model.set_mass_damping("plate", 3000.0);
    add_contact(model, ContactInterface("plate on base", ContactSurface::from_part(mesh, "plate", kShellSteel, 1.0, t),
                                        base_surface(mesh)));
    ExplicitSolver solver(model, quiet(6e-3));
    const RunSummary sum = solver.run();
    double z = 0;
    for (int i = first; i < mesh.node_count(); ++i) z += solver.state().x[i].z() / (mesh.node_count() - first);
    std::printf("plate t = %.1f mm released at %.1f mm: rests at %.4f mm (KE %.2e J, %ld steps)\n", 1e3 * t, 1e3 * z0,
                1e3 * z, sum.energy.kinetic, sum.steps);
    return z;
}
}  // namespace

// With the explicit solver: a 4 mm shell plate dropped on a fixed steel block (top face z = 0) comes
// to rest with its mid-surface 2 mm above the face (its lower surface on it); a 2 mm plate dropped
// on a fixed 6 mm shell plate (mid-surface z = 0) rests 4 mm above it. Tolerance 1 um: the penalty
// springs' static penetration m g / k is ~3e-8 m here, and the rest is the damped settling.
// (Without the thicknesses both would rest on the mid-surface, 2 and 4 mm lower.)
TEST(ContactShellThickness, PlatesComeToRestAtTheirThickness) {
    Mesh block = box_hex8(0.1, 0.1, 0.02, 4, 4, 1, "base");
    block.translate(Vec3(0, 0, -0.02));
    const double z_block = rest_height(
        block, 4e-3, 2.1e-3,
        [](ExplicitModel& m, const Mesh& mesh) {
            m.add_hex8("base", kShellSteel);
            m.fix(mesh.node_set("z0"), Dofs::all());
            m.fix(mesh.node_set("z1"), Dofs::all());
        },
        [](const Mesh& mesh) { return ContactSurface::from_part(mesh, "base", kShellSteel); });
    EXPECT_NEAR(z_block, 2e-3, 1e-6);

    Mesh base = rectangle_quads(0.1, 0.1, 4, 4, ElementShape::Quad4, "base");
    const double z_shell = rest_height(
        base, 2e-3, 4.1e-3,
        [](ExplicitModel& m, const Mesh& mesh) {
            m.add_shells("base", kShellSteel, {.thickness = 6e-3});
            std::vector<int> all;
            for (int b : mesh.blocks_of_part("base"))
                for (int n : mesh.blocks[b].connectivity) all.push_back(n);
            m.fix(all, Dofs::all());
        },
        [](const Mesh& mesh) { return ContactSurface::from_part(mesh, "base", kShellSteel, 1.0, 6e-3); });
    EXPECT_NEAR(z_shell, 4e-3, 1e-6);
}
