#include "modal/deck_run.hpp"

#include <cmath>
#include <cstdlib>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"
#include "input/numbers.hpp"
#include "io/atomic_file.hpp"
#include "io/run_folder.hpp"

namespace fem::modal {
namespace {

// A number as Fortran's E14.7 prints it in ccx's .dat: 0.1234567E+04 (7 digits after "0.").
std::string fortran_e(double v) {
    if (v == 0.0 || !std::isfinite(v)) return v == 0.0 ? "0.0000000E+00" : fmt::format("{}", v);
    const std::string s = fmt::format("{:.6e}", std::abs(v));  // d.dddddde+XX
    const int exponent = std::atoi(s.c_str() + s.find('e') + 1) + 1;
    return fmt::format("{}0.{}{}E{}{:02d}", v < 0 ? "-" : "", s[0], s.substr(2, 6), exponent < 0 ? '-' : '+', std::abs(exponent));
}

}  // namespace

std::vector<std::string> element_types_for(ElementShape shape) {
    switch (shape) {
        case ElementShape::Hex8: return {"C3D8I", "C3D8"};
        case ElementShape::Hex20: return {"C3D20", "C3D20R"};
        case ElementShape::Tet10: return {"C3D10"};
        case ElementShape::Tet4: return {"C3D4"};
        case ElementShape::Quad4: return {"S4"};
        default: return {};
    }
}

int dofs_per_node(std::string_view type) { return type == "S4" || type == "S4R" ? 6 : 3; }

void add_element_block(Model& model, int block, std::string_view type, const ElasticMaterial& m, double thickness,
                       const SolidOptions& options) {
    SolidOptions o = options;
    if (type == "S4" || type == "S4R") {
        if (!(thickness > 0)) throw InputError("element type " + std::string(type) + " needs a shell thickness > 0");
        model.add_block(block, 6, shell_kernel(thickness, m, o.mass));
        return;
    }
    if (type == "C3D8I" && o.mass == solid::MassKind::Consistent) {
        // ccx's C3D8I: the bubble amplitudes are nine DOFs of each element, with mass.
        model.add_block(block, 3, [m](std::span<const Vec3> x, int) {
            solid::Hex8IncompatibleDofs e = solid::hex8_incompatible_dofs(x, m);
            return ElementMatrices{std::move(e.stiffness), std::move(e.mass)};
        }, 9);
        return;
    }
    // With a lumped mass the bubbles carry none, and massless element DOFs are exactly the static
    // condensation of the library's incompatible-modes brick.
    if (type == "C3D8" || type == "C3D8I") o.incompatible_modes = type == "C3D8I";
    if (type == "C3D20" || type == "C3D20R") o.hex20_reduced = type == "C3D20R";
    model.add_block(block, 3, solid_kernel(deck::shape_of_type(type), m, o));
}

void build_deck_model(const deck::Deck& d, Model& model) {
    for (std::size_t b = 0; b < d.mesh.blocks.size(); ++b) {
        const std::string& type = d.block_types[b];
        const deck::Section& s = d.sections[d.block_section[b]];
        SolidOptions o;
        // ccx integrates the tetrahedra's mass with their stiffness rule (4 points C3D10, 1 point C3D4).
        o.tet10_mass_rule = solid::Tet10MassRule::FourPoint;
        o.tet4_mass_rule = solid::Tet4MassRule::Centroid;
        add_element_block(model, static_cast<int>(b), type, d.materials.at(s.material), s.thickness, o);
    }
    for (const deck::Boundary& b : d.boundaries) {
        DofMask mask = 0;
        for (int c = b.first; c <= b.last; ++c) mask |= dof_bit(static_cast<Dof>(c - 1));
        model.fix(b.node, mask);
    }
    for (const deck::Equation& e : d.equations) model.couple({e.node_a, e.node_b}, dof_bit(static_cast<Dof>(e.dof - 1)));
}

std::string ccx_eigenvalue_table(const ModalResult& r) {
    std::string s =
        "\n     E I G E N V A L U E   O U T P U T\n\n"
        " MODE NO    EIGENVALUE                       FREQUENCY   \n"
        "                                     REAL PART            IMAGINARY PART\n"
        "                           (RAD/TIME)      (CYCLES/TIME     (RAD/TIME)\n\n";
    for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
        const double lambda = r.eigenvalues(k);
        // A negative eigenvalue (a rigid-body mode at round-off level) has an imaginary frequency.
        const double omega = lambda >= 0 ? std::sqrt(lambda) : 0.0, imag = lambda < 0 ? std::sqrt(-lambda) : 0.0;
        s += fmt::format("{:7d}{:>16}{:>16}{:>16}{:>16}\n", k + 1, fortran_e(lambda), fortran_e(omega),
                         fortran_e(omega / (2 * std::numbers::pi)), fortran_e(imag));
    }
    return s;
}

std::string run_deck(const std::filesystem::path& path, const DeckRunOptions& o) {
    const deck::Deck d = deck::read_deck(path);
    if (!d.frequency)
        throw InputError("deck '" + path.string() + "' has no *STEP with *FREQUENCY: fem-modal runs frequency decks only");
    const std::filesystem::path output =
        o.output.empty() ? path.parent_path() / (path.stem().string() + "_modes") : o.output;
    io::RunFolder out(output, "fem-modal");
    Model model(d.mesh);
    build_deck_model(d, model);
    const AssembledSystem sys = model.assemble();
    ModalOptions mo;
    mo.modes = o.modes > 0 ? o.modes : d.frequency->modes;
    mo.admit_rigid_body_modes = true;  // as ccx: a free or partly supported deck runs without a shift
    if (o.shapes > mo.modes)
        throw InputError(fmt::format("--shapes {} asks for more mode shapes than the {} modes computed", o.shapes, mo.modes));
    const ModalResult r = solve_modes(sys, mo);
    write_results(out.staging(), d.mesh, sys, r, o.shapes);
    const std::string table = ccx_eigenvalue_table(r);
    io::write_text_file(out.staging() / (path.stem().string() + ".dat"), table);
    out.commit();
    std::string notes;
    for (const std::string& n : d.notes) notes += "note: " + n + "\n";
    return table + "\n" + summary(sys, r) + notes + "  results: " + output.string() + "/{" + path.stem().string() +
           ".dat, frequencies.csv, modes.h5" + (o.shapes == 0 ? "" : ", modes.pvd") + "}\n";
}

}  // namespace fem::modal
