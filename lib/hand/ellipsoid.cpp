#include "hand/ellipsoid.hpp"

#include <numbers>

namespace fem::hand::ellipsoid {

using units::mm;

double spin_stop() { return std::numbers::pi / drum_speed; }

Vec3 centre() { return {conveyor * spin_stop(), 50.8 * mm, 184.0 * mm}; }

Scene scene(const Options& o) {
    Scene s;
    s.hand.drum = stepped_drum(drum_speed);
    s.hand.drum.omega = Curve::steps({{0.0, drum_speed}, {spin_stop(), 0.0}}, "Table 4-5 drum speed");
    // The flip (Table 4-6): about the global z axis through the drum's bottom centre ("drum bottom
    // centre line"), which keeps the symmetry plane z = 184 mm a plane of the model (Sec 9 item 8).
    s.turn.point = Vec3::Zero();
    s.turn.axis = Vec3::UnitZ();  // +z (Sec 9 item 8)
    s.turn.omega = Curve::steps({{0.0, 0.0}, {grasp_end, flip_speed}, {grasp_end + flip_duration, 0.0}},
                                "Table 4-6 flip speed");
    s.gravity = Vec3(0, -9.81, 0);  // Table 4-6; off in the grasp (Sec 9 item 7)
    s.gravity_curve = Curve::step(grasp_end);  // on for the flip
    EllipsoidObject obj;
    obj.part = "ellipsoid";
    obj.semi_axes = semi_axes;
    obj.centre = centre();
    // EllipsoidGrid's default: the football's O-grid, 512 hexahedra for the half
    obj.half = true;
    obj.material = ElasticMaterial::make("ellipsoid rubber (Sec 4.4)", 6.1e6, 0.49, density);
    obj.initial_velocity = Vec3(-conveyor, 0, 0);
    if (o.phase == Phase::grasp) {
        obj.carried_velocity = Vec3(-conveyor, 0, 0);
        obj.carried_scale = Curve::steps({{0.0, 1.0}, {spin_stop(), 0.0}}, "Table 4-5 conveyor");
    }
    s.objects.push_back(obj);
    const contact::FrictionLaw mu{mu_static, mu_dynamic, 0.0};  // c_d = 0: mu = mu_s = 0.4
    s.contacts.push_back({"fingers", "ellipsoid", mu, true});
    s.contacts.push_back({"ellipsoid", "drum", mu, false});
    // The fingers against their mirror images across z = 184 mm (as football.cpp): without it A and
    // C reach 1.3 and 1.1 mm past the plane in the grasp (study README reconstruction 9).
    s.mirror_contact = true;
    return s;
}

}  // namespace fem::hand::ellipsoid
