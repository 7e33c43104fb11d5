#pragma once
// Linear isotropic elastic material and the wave speeds that set the explicit time step
// (thesis Table 2-1, last column).
#include <string>

namespace fem {

/// Isotropic linear elastic material in SI units. Construct through make() so that non-physical
/// values (E <= 0, rho <= 0, nu outside (-1, 0.5)) are refused with the material named.
struct ElasticMaterial {
    std::string name;
    double youngs_modulus = 0.0;  // E [Pa]
    double poissons_ratio = 0.0;  // nu [-]
    double density = 0.0;         // rho [kg/m^3]

    /// Validated constructor: throws fem::InputError naming `name` and the offending value.
    static ElasticMaterial make(std::string name, double E, double nu, double rho);

    double shear_modulus() const;  // G = E / (2 (1 + nu))
    double bulk_modulus() const;   // B = E / (3 (1 - 2 nu)), thesis Eq 2-33
    double lame_lambda() const;    // lambda = E nu / ((1 + nu)(1 - 2 nu))
};

/// Wave speed in a slender bar (beam row of Table 2-1): c = sqrt(E / rho).
double bar_wave_speed(const ElasticMaterial& m);

/// Wave speed in a plane-stress plate (shell rows of Table 2-1): c = sqrt(E / (rho (1 - nu^2))).
double plate_wave_speed(const ElasticMaterial& m);

/// Dilatational wave speed in a 3D solid (solid rows of Table 2-1):
/// c = sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))).
double dilatational_wave_speed(const ElasticMaterial& m);

}  // namespace fem
