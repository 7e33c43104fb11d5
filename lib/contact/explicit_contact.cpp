#include "contact/explicit_contact.hpp"

#include <cmath>
#include <limits>

namespace fem::contact {

void ContactProvider::initialize(const NodalState& s) {
    w2_ = c_.stability_frequency_squared(s.mass);
    first_ = true;
}

void ContactProvider::add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>&) {
    const double dt = first_ ? 0.0 : t - t_prev_;  // v(n-1/2) moved the nodes over [t_{n-1}, t_n]
    first_ = false;
    t_prev_ = t;
    c_.evaluate(s.x, s.v, t, dt, force);
}

double ContactProvider::stable_time_step(const NodalState&) const {
    return w2_ > 0.0 ? 2.0 / std::sqrt(w2_) : std::numeric_limits<double>::infinity();
}

ContactReport ContactProvider::contact_report() const {
    return {true, c_.max_penetration(), c_.max_penetration_fraction(), c_.stored_energy(), c_.dissipated_energy()};
}

ContactInterface& add_contact(ExplicitModel& model, ContactInterface contact) {
    auto& p = model.add_force_provider(std::make_unique<ContactProvider>(std::move(contact)));
    return static_cast<ContactProvider&>(p).contact();
}

Resultant support_reaction(const ExplicitSolver& solver, const std::vector<int>& nodes, const Vec3& about) {
    return resultant(nodes, solver.state().f, solver.state().x, about);
}

}  // namespace fem::contact
