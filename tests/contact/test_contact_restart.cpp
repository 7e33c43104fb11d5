// Restart of an explicit run with contact (ExplicitOptions::restart_*): a run stopped at T/2, dumped,
// and continued by a fresh model and solver from the dump ends bit for bit where the uninterrupted
// run ends: positions, velocities, energies, contact forces and energies, histories, the VTU series.
// The model has everything with state: a rubber block (hex8, bulk viscosity) pressed by gravity onto
// a rigid turntable that starts turning under it (a rigid part with a speed schedule), friction with the
// velocity-dependent Eq 2-35 (stick, then slip: the friction springs and the segment each node
// sticks to carry over), mass damping, histories.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "../explicit/explicit_test_support.hpp"
#include "contact/contact.hpp"
#include "contact/explicit_contact.hpp"
#include "core/error.hpp"

using namespace fem;
using namespace fem::contact;
namespace fs = std::filesystem;

namespace {
const ElasticMaterial kCompressibleRubber = ElasticMaterial::make("rubber", 2e6, 0.3, 1000);

Mesh block_on_pallet() {
    Mesh mesh = box_hex8(0.03, 0.03, 0.015, 3, 3, 2, "block");
    // Resting on the pallet (touching it).
    mesh.append(parallelogram_quad4(Vec3(0.05, 0.015, 0), Vec3(0.2, 0, 0), Vec3(0, 0.1, 0), 8, 4, "pallet"));
    return mesh;
}

struct PalletModel {
    std::unique_ptr<ExplicitModel> model;
    ContactInterface* contact = nullptr;
};

// with_contact = false leaves the interface out (a model that does not match the dump).
PalletModel make_model(const Mesh& mesh, bool with_contact = true) {
    PalletModel r;
    r.model = std::make_unique<ExplicitModel>(mesh);
    r.model->add_hex8("block", kCompressibleRubber);
    r.model->set_mass_damping("block", 20.0);
    // A downward body force ramped over 10 ms (5 g: the block stays pressed on the pallet, no bounce).
    r.model->set_gravity(Vec3(0, 0, -49.05), Curve({{0, 0}, {0.01, 1}}, "press"));
    // A turntable under the block, turning about a vertical axis 45 mm from the block's centre: at
    // rest for 10 ms, then up to 4 rad/s by 30 ms, faster than friction can drag the block along, so
    // nodes stick and slip in directions that change from node to node and cycle to cycle.
    r.model->add_rigid_part("pallet", RigidMotion::rotation(Vec3(0.06, 0.015, 0), Vec3::UnitZ(),
                                                            Curve({{0, 0}, {0.01, 0}, {0.03, 4}})));
    if (with_contact) {
        ContactOptions co;
        co.friction = {0.4, 0.3, 5.0};
        r.contact = &add_contact(*r.model, ContactInterface("block on pallet", ContactSurface::from_part(mesh, "block", kCompressibleRubber),
                                                            ContactSurface::rigid_part(mesh, "pallet", 5e-3), co));
    }
    return r;
}

ExplicitOptions options(double end, const fs::path& dir) {
    ExplicitOptions o = test::quiet(end);
    o.name = "block on pallet";
    o.history_nodes = {{"corner", 0}, {"top", 20}};
    o.history_interval = 1e-3;
    o.pvd_path = dir / "run.pvd";
    o.vtu_interval = 0.01;
    return o;
}

bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}
}  // namespace

TEST(ContactRestart, RestartedRunContinuesBitIdentically) {
    const double T = 0.05;
    const Mesh mesh = block_on_pallet();
    const fs::path dir = fs::temp_directory_path() / "fem_contact_restart_test";
    fs::remove_all(dir);
    // Uninterrupted 0..T.
    PalletModel a = make_model(mesh);
    ExplicitSolver sa(*a.model, options(T, dir / "a"));
    const RunSummary ra = sa.run();
    // 0..T/2 with a dump at the end, then a fresh model and solver from the dump to T.
    PalletModel b = make_model(mesh);
    ExplicitOptions ob = options(0.5 * T, dir / "b");
    ob.restart_times = {0.5 * T};
    ob.restart_dir = dir / "dumps";
    ExplicitSolver sb(*b.model, ob);
    sb.run();
    ASSERT_EQ(sb.restart_files().size(), 1u);
    const fs::path dump = sb.restart_files()[0];
    EXPECT_EQ(dump, ExplicitSolver::latest_restart(ob.restart_dir, ob.name));
    EXPECT_TRUE(fs::exists(dump));
    EXPECT_FALSE(fs::exists(fs::path(dump.string() + ".partial")));  // written atomically
    PalletModel c = make_model(mesh);
    ExplicitOptions oc = options(T, dir / "b");
    oc.restart_from = dump;
    ExplicitSolver sc(*c.model, oc);
    EXPECT_EQ(sc.time(), sb.time());
    EXPECT_EQ(sc.step(), sb.step());
    const RunSummary rc = sc.run();

    std::printf("[ restart ] dump at t = %.6g s (step %ld) of %ld steps; friction dissipated %.4g J by then, %.4g J "
                "at the end; contact energy %.4g J\n",
                sb.time(), sb.step(), ra.steps, b.contact->dissipated_energy(), a.contact->dissipated_energy(),
                a.contact->energy());
    // At the dump the block is on the turntable with friction springs loaded, some nodes slipping.
    EXPECT_GT(b.contact->dissipated_energy(), 0.0);
    int slipping = 0, loaded = 0;
    for (const auto& cp : b.contact->contacts()) slipping += cp.slipping, loaded += cp.tangential_force.norm() > 0;
    std::printf("[ restart ] at the dump: %zu nodes in contact, %d with a friction force, %d slipping\n",
                b.contact->contacts().size(), loaded, slipping);
    EXPECT_GE(loaded, 10);
    EXPECT_GT(a.contact->dissipated_energy(), b.contact->dissipated_energy());  // and after it
    EXPECT_EQ(rc.steps, ra.steps);
    EXPECT_EQ(sc.time(), sa.time());
    EXPECT_TRUE(same_bits(sc.state().x, sa.state().x));
    EXPECT_TRUE(same_bits(sc.state().v, sa.state().v));
    EXPECT_TRUE(same_bits(sc.state().f, sa.state().f));
    const EnergySummary &ea = ra.energy, &ec = rc.energy;
    for (auto [x, y] : {std::pair{ea.kinetic, ec.kinetic}, {ea.internal, ec.internal}, {ea.hourglass, ec.hourglass},
                        {ea.damping, ec.damping}, {ea.viscous, ec.viscous}, {ea.external, ec.external},
                        {ea.contact, ec.contact}, {ea.initial, ec.initial}, {ea.balance_error, ec.balance_error},
                        {ea.max_abs_balance_error, ec.max_abs_balance_error}})
        EXPECT_EQ(x, y);
    EXPECT_EQ(a.contact->force_on_master(), c.contact->force_on_master());
    EXPECT_EQ(a.contact->stored_energy(), c.contact->stored_energy());
    EXPECT_EQ(a.contact->dissipated_energy(), c.contact->dissipated_energy());
    EXPECT_EQ(a.contact->rigid_work(), c.contact->rigid_work());
    EXPECT_EQ(a.contact->rebuilds(), c.contact->rebuilds());
    EXPECT_EQ(a.contact->cycles(), c.contact->cycles());
    EXPECT_EQ(a.contact->contacts().size(), c.contact->contacts().size());
    EXPECT_EQ(ra.min_dt, rc.min_dt);
    EXPECT_EQ(ra.interfaces[0].max_penetration, rc.interfaces[0].max_penetration);
    // The histories of the restarted run cover 0..T, sample for sample.
    const History &ha = sa.history(), &hc = sc.history();
    EXPECT_EQ(ha.time, hc.time);
    EXPECT_EQ(ha.kinetic, hc.kinetic);
    EXPECT_EQ(ha.contact, hc.contact);
    EXPECT_EQ(ha.max_von_mises, hc.max_von_mises);
    ASSERT_EQ(hc.nodes.size(), 2u);
    EXPECT_TRUE(same_bits(ha.nodes[1].displacement, hc.nodes[1].displacement));
    // The VTU series continues: the same number of files as the uninterrupted run's.
    int files_a = 0, files_b = 0;
    for (const auto& e : fs::directory_iterator(dir / "a")) files_a += e.path().extension() == ".vtu";
    for (const auto& e : fs::directory_iterator(dir / "b")) files_b += e.path().extension() == ".vtu";
    EXPECT_EQ(files_a, files_b);
    fs::remove_all(dir);
}

// A restart file is refused, naming what differs, by a model without its contact interface, with
// another mesh, or with other element groups.
TEST(ContactRestart, RestartFileOfAnotherModelIsRefused) {
    const Mesh mesh = block_on_pallet();
    const fs::path dir = fs::temp_directory_path() / "fem_contact_restart_refused";
    fs::remove_all(dir);
    PalletModel b = make_model(mesh);
    ExplicitOptions ob = options(0.005, dir);
    ob.pvd_path.clear();
    ob.restart_times = {0.005};
    ob.restart_dir = dir;
    ExplicitSolver sb(*b.model, ob);
    sb.run();
    ASSERT_EQ(sb.restart_files().size(), 1u);
    auto refusal = [&](ExplicitModel& model) {
        ExplicitOptions o = options(0.01, dir);
        o.pvd_path.clear();
        o.restart_from = sb.restart_files()[0];
        return test::input_error([&] { ExplicitSolver s(model, o); });
    };
    PalletModel no_contact = make_model(mesh, false);
    EXPECT_NE(refusal(*no_contact.model).find("contact interface (force provider) 0 is 'block on pallet' in the file but "
                                              "missing in the model"),
              std::string::npos)
        << refusal(*no_contact.model);
    Mesh bigger = block_on_pallet();
    bigger.append(box_hex8(0.01, 0.01, 0.01, 1, 1, 1, "extra"));
    PalletModel other_mesh = make_model(bigger);
    EXPECT_NE(refusal(*other_mesh.model)
                  .find(fmt::format("the node count is {} in the file but {}", mesh.node_count(), bigger.node_count())),
              std::string::npos)
        << refusal(*other_mesh.model);
    ExplicitModel other_groups(mesh);
    other_groups.add_hex8("block", kCompressibleRubber);
    other_groups.add_point_mass("tip", 0, 1e-3);
    other_groups.add_force_provider(std::make_unique<ContactProvider>(
        ContactInterface("block on pallet", ContactSurface::from_part(mesh, "block", kCompressibleRubber),
                         ContactSurface::rigid_part(mesh, "pallet", 5e-3))));
    EXPECT_NE(refusal(other_groups).find("element group 1 is missing in the file but part 'tip'"), std::string::npos)
        << refusal(other_groups);
    ExplicitOptions o = options(0.01, dir);
    o.restart_from = dir / "nothere.h5";
    PalletModel ok = make_model(mesh);
    EXPECT_THROW(ExplicitSolver(*ok.model, o), InputError);
    EXPECT_THROW(ExplicitSolver::latest_restart(dir, "another run"), InputError);
    fs::remove_all(dir);
}
