#include "contact/friction.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::contact {

double FrictionLaw::mu(double v) const { return mu_dynamic + (mu_static - mu_dynamic) * std::exp(-decay * std::abs(v)); }

void FrictionLaw::validate(const char* where) const {
    if (!(mu_static >= 0.0) || !(mu_dynamic >= 0.0) || !(decay >= 0.0))
        throw InputError(fmt::format("{}: friction coefficients mu_s = {}, mu_d = {} and decay c_d = {} must be >= 0",
                                     where, mu_static, mu_dynamic, decay));
}

FrictionUpdate coulomb_return_map(const Vec3& f_old, const Vec3& n, const Vec3& slip, double speed, double k_t,
                                  double fn, const FrictionLaw& law) {
    FrictionUpdate r;
    r.mu = law.mu(speed);
    // Carry the stored force onto the current tangent plane, keeping its magnitude (the contact
    // point's frame rotates with the surface).
    Vec3 f = f_old - f_old.dot(n) * n;
    const double fo = f_old.norm(), ft = f.norm();
    if (ft > 0.0) f *= fo / ft;
    const Vec3 du = slip - slip.dot(n) * n;
    const Vec3 trial = f - k_t * du;
    const double limit = r.mu * std::max(fn, 0.0);
    const double t = trial.norm();
    if (t <= limit) {
        r.force = trial;  // stick
        return r;
    }
    r.slipping = true;
    r.force = trial * (limit / t);
    r.dissipation = limit * (t - limit) / k_t;
    return r;
}

}  // namespace fem::contact
