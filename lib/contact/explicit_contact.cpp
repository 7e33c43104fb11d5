#include "contact/explicit_contact.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/hdf5.hpp"

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

ContactReport contact_report(const ContactInterface& c) {
    return {true,
            c.max_penetration(),
            c.max_penetration_fraction(),
            c.stored_energy(),
            c.dissipated_energy(),
            c.force_on_master(),
            static_cast<int>(c.contacts().size())};
}

ContactReport ContactProvider::contact_report() const { return contact::contact_report(c_); }

void ContactProvider::save_state(io::H5Writer& w, const std::string& prefix) const {
    w.write(prefix + "provider", std::vector<double>{t_prev_, first_ ? 1.0 : 0.0});
    c_.save_state(w, prefix + "interface/");
}

void ContactProvider::restore_state(const io::H5Reader& r, const std::string& prefix) {
    const auto v = r.read(prefix + "provider");
    if (v.size() != 2)
        throw InputError(fmt::format("restart file '{}': contact '{}': bad {}provider", r.path().string(), name(), prefix));
    t_prev_ = v[0];
    first_ = v[1] != 0.0;
    c_.restore_state(r, prefix + "interface/");
}

ContactInterface& add_contact(ExplicitModel& model, ContactInterface contact) {
    auto& p = model.add_force_provider(std::make_unique<ContactProvider>(std::move(contact)));
    return static_cast<ContactProvider&>(p).contact();
}

Resultant support_reaction(const ExplicitSolver& solver, const std::vector<int>& nodes, const Vec3& about) {
    return resultant(nodes, solver.state().f, solver.state().x, about);
}

}  // namespace fem::contact
