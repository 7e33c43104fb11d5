#pragma once
// Contact in the explicit solver: a ContactInterface as the solver's ForceProvider
// (explicit/element_group.hpp), and the support reaction.
//
//   Mesh mesh = ...;                                  // finger (hex8) + object parts
//   ExplicitModel model(mesh);
//   model.add_hex8("finger", rubber);  model.add_hex8("object", aluminium);
//   contact::ContactOptions co;  co.friction = {0.6, 0.6, 0.0};           // Table 3-6
//   auto& c = contact::add_contact(model, contact::ContactInterface("finger on object",
//       contact::ContactSurface::from_part(mesh, "finger", rubber),
//       contact::ContactSurface::from_part(mesh, "object", aluminium), co));
//   model.prescribe_motion(mesh.node_set("root"),                          // root on the drum
//       RigidMotion::rotation(drum_centre, Vec3::UnitZ(), Curve::constant(2.095)));
//   model.add_rigid_part("ground", RigidMotion::fixed());                   // a rigid master
//   contact::add_contact(model, contact::ContactInterface("object on ground",
//       contact::ContactSurface::from_part(mesh, "object", aluminium),
//       contact::ContactSurface::rigid_part(mesh, "ground", 0.01), co));
//   ExplicitSolver solver(model, opt);
//   solver.observer = [&](const ExplicitSolver& s) { ... c.force_on_master(), c.contacts() ... };
//
// Timing: the solver calls the provider at x(n) with v(n-1/2), before the velocity update; the
// friction slip increment of that call is v(n-1/2) (t_n - t_{n-1}). The solver's "contact" energy
// is minus the work of the contact forces on the structure (penalty springs + friction + the work
// of moving rigid masters); ContactInterface::energy() gives the stored + dissipated split.
#include <vector>

#include "contact/contact.hpp"
#include "explicit/solver.hpp"

namespace fem::contact {

class ContactProvider final : public ForceProvider {
public:
    explicit ContactProvider(ContactInterface contact) : c_(std::move(contact)) {}
    std::string name() const override { return c_.name(); }
    void initialize(const NodalState& s) override;
    void add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) override;
    /// 2 / omega of the penalty springs (ContactInterface::stability_frequency_squared).
    double stable_time_step(const NodalState& s) const override;
    double search_seconds() const override { return c_.search_seconds(); }
    ContactReport contact_report() const override;
    /// "contact_pressure" (ContactInterface::nodal_pressure).
    std::vector<std::pair<std::string, std::vector<double>>> point_fields(const NodalState& s) const override {
        return {{"contact_pressure", c_.nodal_pressure(s.x)}};
    }
    void save_state(io::H5Writer& w, const std::string& prefix) const override;
    void restore_state(const io::H5Reader& r, const std::string& prefix) override;
    ContactInterface& contact() { return c_; }
    const ContactInterface& contact() const { return c_; }

private:
    ContactInterface c_;
    double w2_ = 0.0;
    double t_prev_ = 0.0;
    bool first_ = true;
};

/// The interface's statistics as the run summary reads them (ContactProvider::contact_report); the
/// count of active contacts is that of contacts() (a node on two passes counts twice).
ContactReport contact_report(const ContactInterface& contact);

/// Adds the interface to the model as a force provider; the returned reference stays valid for the
/// model's life (outputs: force_on_master(), contacts(), energies).
ContactInterface& add_contact(ExplicitModel& model, ContactInterface contact);

/// Reaction force and moment (about `about`) of the supports at `nodes` (fixed nodes carrying no
/// load or contact themselves): the sum of the internal (resisting) forces there, e.g. the F/T
/// sensor of thesis Fig 3-21 with its top surface fixed.
Resultant support_reaction(const ExplicitSolver& solver, const std::vector<int>& nodes, const Vec3& about);

}  // namespace fem::contact
