// SAE J211 / ISO 6487 CFC filter (damping/signal.hpp) against the closed-form response of its design:
// two passes of a two-pole Butterworth with design frequency fd = 2.0775 CFC give the zero-phase
// amplitude gain 1 / (1 + r^4), r = tan(pi f T) / tan(pi fd T) the bilinear transform's warped ratio.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "damping/signal.hpp"

using namespace fem;
using namespace fem::damping;
using std::numbers::pi;

namespace {

SampledSignal sine(double f, double rate, double duration) {
    SampledSignal s{0.0, 1.0 / rate, {}};
    for (int i = 0; i * s.dt < duration; ++i) s.x.push_back(std::sin(2 * pi * f * i * s.dt));
    return s;
}

// Amplitude in the middle half of the record, away from the start-up transients of both passes.
double middle_amplitude(const SampledSignal& s) {
    double a = 0.0;
    for (std::size_t i = s.size() / 4; i < 3 * s.size() / 4; ++i) a = std::max(a, std::abs(s.x[i]));
    return a;
}

double gain_db(double f, double cfc) {
    return 20 * std::log10(middle_amplitude(cfc_filter(sine(f, 10000.0, 2.0), cfc)));
}

}  // namespace

TEST(CfcFilter, GainFollowsTheFourPoleButterworth) {
    for (double f : {10.0, 60.0, 100.0, 200.0, 400.0}) {
        const double fd = 2.0775 * 60.0, T = 1e-4;
        const double r = std::tan(pi * f * T) / std::tan(pi * fd * T);
        const double expected = -20 * std::log10(1 + std::pow(r, 4));
        EXPECT_NEAR(gain_db(f, 60.0), expected, 0.05) << f << " Hz";
    }
}

TEST(CfcFilter, MeetsTheJ211CorridorForCfc60) {
    // J211: flat within +0.5 / -1 dB up to CFC; about -3 dB at 1.667 CFC; strongly attenuating beyond.
    EXPECT_GT(gain_db(60.0, 60.0), -1.0);
    EXPECT_LT(gain_db(60.0, 60.0), 0.5);
    EXPECT_NEAR(gain_db(100.0, 60.0), -3.0, 0.25);
    EXPECT_LT(gain_db(1000.0, 60.0), -60.0);
}

TEST(CfcFilter, HasNoPhaseShiftAndKeepsAConstant) {
    // A smooth pulse keeps its peak time (forward + backward pass); a constant record is unchanged.
    SampledSignal s{0.0, 1e-4, {}};
    for (int i = 0; i < 10000; ++i) s.x.push_back(3.0 + std::exp(-std::pow((i * 1e-4 - 0.5) / 0.02, 2)));
    const auto y = cfc_filter(s, 60.0);
    std::size_t peak = 0;
    for (std::size_t i = 0; i < y.size(); ++i)
        if (y.x[i] > y.x[peak]) peak = i;
    EXPECT_NEAR(y.time(peak), 0.5, 1e-4);
    EXPECT_NEAR(y.x.front(), 3.0, 1e-9);
    EXPECT_NEAR(y.x.back(), 3.0, 1e-9);
}

TEST(CfcFilter, RefusesUndersampledRecordsAndBadClasses) {
    EXPECT_THROW(cfc_filter(sine(10.0, 500.0, 1.0), 60.0), InputError);  // 500 Hz < 10 x 60 Hz
    EXPECT_THROW(cfc_filter(sine(10.0, 10000.0, 1.0), 0.0), InputError);
    EXPECT_THROW(cfc_filter(sine(10.0, 10000.0, 1.0), -60.0), InputError);
}
