#include "hand/football.hpp"

#include <fmt/format.h>

namespace fem::hand::football {

using units::mm;

Curve Case::schedule() const {
    if (t_switch < 0) return Curve::constant(fast);
    return Curve::steps({{0.0, fast}, {t_switch, slow}}, fmt::format("Table 4-4 case {} pallet speed", id));
}

std::vector<Case> table_4_4() { return {{1, -1.0}, {2, 1.38}, {3, 1.28}, {4, 1.19}, {5, 1.06}}; }

std::vector<std::pair<std::string, std::string>> neighbour_pairs() {
    return {{"A", "B"}, {"C", "D"}, {"D", "E"}, {"A", "C"}, {"A", "D"}, {"B", "D"}, {"B", "E"}};
}

Scene scene(const Case& c) {
    Scene s;
    s.gravity = Vec3(0, -9.81, 0);  // Table 4-3, -y (THESIS_CH4_5 Sec 9 item 1)
    EllipsoidObject ball;
    ball.part = "football";
    ball.semi_axes = semi_axes;
    ball.centre = centre;
    // EllipsoidGrid's default: 512 elements, 678 nodes (Table 4-2: 512 / 677), inner block 0.4
    ball.half = true;
    ball.material = ElasticMaterial::make("football rubber (Table 4-2)", 6.1e6, 0.49, 275.0);
    // (Table 4-2's 275 kg/m^3, the FE model's input; the raw weight, mass = half_mass, was the first
    // session's reconstruction: THESIS_CH4_5 Sec 10 item 2, study README)
    ball.initial_velocity = Vec3(-fast, 0, 0);  // riding the pallet (Sec 9 item 6)
    s.objects.push_back(ball);
    Plate pallet;
    pallet.part = "pallet";
    // Top at the football's bottom (y = 50.8 - 66 mm), 200 (x) x 50 (z) mm, from the plane z = 184
    // towards the drum, centred 8 mm downstream of the football (Sec 9 item 6).
    pallet.centre = Vec3(centre.x() - pallet_offset, centre.y() - semi_axes.y(), 159 * mm);
    pallet.u = Vec3(200 * mm, 0, 0);
    pallet.v = Vec3(0, 0, -50 * mm);
    pallet.speed = c.schedule();
    s.plates.push_back(pallet);
    const contact::FrictionLaw mu{mu_static, mu_dynamic, 0.0};  // c_d = 0: mu = mu_s (the thesis's effective friction)
    // Every finger against the football as one surface (one search, one stable-step bound: five
    // separate pairs would each add a penalty frequency to the step).
    s.contacts.push_back({"fingers", "football", mu, true});
    s.contacts.push_back({"football", "pallet", mu, false});
    s.contacts.push_back({"football", "drum", mu, false});
    // The fingers against their mirror images across z = 184 mm (the other drum of the full hand):
    // A and B reach 13 mm past the plane (study README reconstruction 9).
    s.mirror_contact = true;
    return s;
}

}  // namespace fem::hand::football
