#pragma once
// Coulomb friction (thesis Sec 2.3.7, Eq 2-34 and 2-35) as an elastic-plastic tangential spring.
//
// The tangential force on a slave node is the force of an elastic spring of stiffness k_t (the
// normal penalty stiffness) stretched by the accumulated tangential slip, limited by the Coulomb
// cone |f_t| <= mu f_n (Eq 2-34). Each cycle: the previous force is carried onto the current
// tangent plane (magnitude kept), the trial force is f_trial = f_old - k_t du_t (du_t: tangential
// relative displacement of the slave node against the master point in the cycle), and when
// |f_trial| > mu f_n it is returned radially onto the cone (slip). A node held by a tangential pull
// below mu_s f_n therefore sticks (it only stretches the spring), unlike a velocity-only rule.
// mu follows Eq 2-35: mu = mu_d + (mu_s - mu_d) exp(-c_d |v_r|), v_r the tangential relative speed.
// Dissipation of a slipping cycle: mu f_n (|f_trial| - mu f_n) / k_t (force times plastic slip).
#include "core/types.hpp"

namespace fem::contact {

struct FrictionLaw {
    double mu_static = 0.0;    // mu_s
    double mu_dynamic = 0.0;   // mu_d
    double decay = 0.0;        // c_d [s/m] (thesis: presumed 0, and then Eq 2-35 gives mu = mu_s always)
    /// Eq 2-35.
    double mu(double relative_speed) const;
    bool active() const { return mu_static > 0.0 || mu_dynamic > 0.0; }
    /// Throws InputError for negative coefficients.
    void validate(const char* where) const;
};

struct FrictionUpdate {
    Vec3 force = Vec3::Zero();   // tangential force on the slave node (in the tangent plane)
    double mu = 0.0;             // coefficient used
    bool slipping = false;
    double dissipation = 0.0;    // energy dissipated this cycle [J]
};

/// One return-mapping step. f_old: previous tangential force (any plane); normal: current unit
/// normal; slip: relative displacement increment of the slave node against the master point
/// (only its tangential part is used); speed: tangential relative speed for Eq 2-35; k_t > 0;
/// fn >= 0 the normal force magnitude.
FrictionUpdate coulomb_return_map(const Vec3& f_old, const Vec3& normal, const Vec3& slip, double speed, double k_t,
                                  double fn, const FrictionLaw& law);

}  // namespace fem::contact
