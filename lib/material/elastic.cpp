#include "material/elastic.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace fem {

ElasticMaterial ElasticMaterial::make(std::string name, double E, double nu, double rho) {
    auto refuse = [&](const char* what, double value, const char* rule) {
        std::ostringstream msg;
        msg << "material '" << name << "': " << what << " = " << value << " is not physical (" << rule << ")";
        throw InputError(msg.str());
    };
    if (!(E > 0.0) || !std::isfinite(E)) refuse("Young's modulus E", E, "needs E > 0");
    if (!(rho > 0.0) || !std::isfinite(rho)) refuse("density rho", rho, "needs rho > 0");
    if (!(nu > -1.0 && nu < 0.5)) refuse("Poisson's ratio nu", nu, "needs -1 < nu < 0.5");
    return ElasticMaterial{std::move(name), E, nu, rho};
}

double ElasticMaterial::shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poissons_ratio)); }

double ElasticMaterial::bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poissons_ratio)); }

double ElasticMaterial::lame_lambda() const {
    const double nu = poissons_ratio;
    return youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double bar_wave_speed(const ElasticMaterial& m) { return std::sqrt(m.youngs_modulus / m.density); }

double plate_wave_speed(const ElasticMaterial& m) {
    const double nu = m.poissons_ratio;
    return std::sqrt(m.youngs_modulus / (m.density * (1.0 - nu * nu)));
}

double dilatational_wave_speed(const ElasticMaterial& m) {
    const double nu = m.poissons_ratio;
    return std::sqrt(m.youngs_modulus * (1.0 - nu) / (m.density * (1.0 + nu) * (1.0 - 2.0 * nu)));
}

}  // namespace fem
