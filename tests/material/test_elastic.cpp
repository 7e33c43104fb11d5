#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "material/elastic.hpp"

using fem::ElasticMaterial;

TEST(ElasticMaterial, DerivedModuli) {
    const auto steel = ElasticMaterial::make("steel", 210e9, 0.28, 7700);
    EXPECT_NEAR(steel.shear_modulus(), 210e9 / 2.56, 1e-3);
    EXPECT_NEAR(steel.bulk_modulus(), 210e9 / (3 * 0.44), 1e-3);  // Eq 2-33
    EXPECT_NEAR(steel.lame_lambda(), 210e9 * 0.28 / (1.28 * 0.44), 1e-3);
}

TEST(ElasticMaterial, WaveSpeedsOfTable21) {
    const auto al = ElasticMaterial::make("AL6061", 69e9, 0.33, 2700);
    EXPECT_NEAR(fem::bar_wave_speed(al), 5055.2503, 1e-3);
    EXPECT_NEAR(fem::plate_wave_speed(al), 5355.2462, 1e-3);
    EXPECT_NEAR(fem::dilatational_wave_speed(al), 6153.3949, 1e-3);
    // nu = 0: all three coincide.
    const auto cork = ElasticMaterial::make("cork", 20e6, 0.0, 200);
    EXPECT_DOUBLE_EQ(fem::bar_wave_speed(cork), fem::plate_wave_speed(cork));
    EXPECT_DOUBLE_EQ(fem::bar_wave_speed(cork), fem::dilatational_wave_speed(cork));
}

TEST(ElasticMaterial, RefusesNonPhysicalValuesNamingTheMaterial) {
    EXPECT_THROW(ElasticMaterial::make("rubber", 6.1e6, 0.5, 1000), fem::InputError);
    EXPECT_THROW(ElasticMaterial::make("rubber", 0.0, 0.49, 1000), fem::InputError);
    EXPECT_THROW(ElasticMaterial::make("rubber", 6.1e6, 0.49, -1), fem::InputError);
    EXPECT_THROW(ElasticMaterial::make("rubber", NAN, 0.49, 1000), fem::InputError);
    try {
        ElasticMaterial::make("finger rubber", 6.1e6, 0.55, 1000);
        FAIL() << "nu = 0.55 accepted";
    } catch (const fem::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("finger rubber"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("0.55"), std::string::npos);
    }
}
