#include "io/vtu.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace fem::io {
namespace {

int vtk_cell_type(ElementShape s) {
    switch (s) {
        case ElementShape::Point1: return 1;   // VTK_VERTEX
        case ElementShape::Beam2: return 3;    // VTK_LINE
        case ElementShape::Tri3: return 5;     // VTK_TRIANGLE
        case ElementShape::Quad4: return 9;    // VTK_QUAD
        case ElementShape::Quad8: return 23;   // VTK_QUADRATIC_QUAD
        case ElementShape::Tet4: return 10;    // VTK_TETRA
        case ElementShape::Tet10: return 24;   // VTK_QUADRATIC_TETRA
        case ElementShape::Hex8: return 12;    // VTK_HEXAHEDRON
    }
    return 0;
}

// Our tet10 order is Gmsh's (mid-edge nodes on edges 01 12 20 03 23 13, see mesh/element_shape.hpp);
// VTK's quadratic tetra wants 01 12 02 03 13 23, so the last two mid-edge nodes are swapped
// on output.
int vtk_node(ElementShape s, int k) {
    if (s == ElementShape::Tet10 && (k == 8 || k == 9)) return 17 - k;
    return k;
}

void write_field(std::ostream& out, const Field& f, std::size_t expected_count, const char* where) {
    if (f.values.size() != expected_count * f.components)
        throw std::invalid_argument(std::string("VTU ") + where + " field '" + f.name + "' has " +
                                    std::to_string(f.values.size()) + " values, expected " +
                                    std::to_string(expected_count * f.components));
    out << "        <DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\"" << f.components
        << "\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < f.values.size(); ++i) out << f.values[i] << ((i + 1) % 9 ? ' ' : '\n');
    out << "\n        </DataArray>\n";
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const Mesh& mesh, const VtuData& data, std::span<const Vec3> x) {
    if (x.empty()) x = mesh.nodes;
    if (static_cast<int>(x.size()) != mesh.node_count())
        throw std::invalid_argument("VTU coordinates do not match the mesh's node count");
    AtomicFile file(path);
    auto& out = file.stream();
    out << std::setprecision(9);
    const int cells = mesh.element_count();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" << mesh.node_count() << "\" NumberOfCells=\"" << cells
        << "\">\n      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const auto& p : x) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    out << "        </DataArray>\n      </Points>\n      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& b : mesh.blocks)
        for (int e = 0; e < b.size(); ++e) {
            auto conn = b.element(e);
            for (int k = 0; k < b.nodes_per_element(); ++k) out << conn[vtk_node(b.shape, k)] << ' ';
            out << '\n';
        }
    out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    long offset = 0;
    for (const auto& b : mesh.blocks)
        for (int e = 0; e < b.size(); ++e) out << (offset += b.nodes_per_element()) << '\n';
    out << "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (const auto& b : mesh.blocks)
        for (int e = 0; e < b.size(); ++e) out << vtk_cell_type(b.shape) << '\n';
    out << "        </DataArray>\n      </Cells>\n      <PointData>\n";
    for (const auto& f : data.point_fields) write_field(out, f, mesh.node_count(), "point");
    out << "      </PointData>\n      <CellData>\n";
    Field part{"part", 1, {}};
    for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b) part.values.insert(part.values.end(), mesh.blocks[b].size(), b);
    write_field(out, part, cells, "cell");
    for (const auto& f : data.cell_fields) write_field(out, f, cells, "cell");
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    file.commit();
}

PvdSeries::PvdSeries(std::filesystem::path pvd_path) : path_(std::move(pvd_path)) {}

void PvdSeries::add(double time, const Mesh& mesh, const VtuData& data, std::span<const Vec3> x) {
    std::ostringstream name;
    name << path_.stem().string() << '_' << std::setw(4) << std::setfill('0') << entries_.size() << ".vtu";
    write_vtu(path_.parent_path() / name.str(), mesh, data, x);
    entries_.emplace_back(time, name.str());
    write();
}

void PvdSeries::write() const {
    std::ostringstream out;
    out << std::setprecision(9) << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& [t, file] : entries_) out << "    <DataSet timestep=\"" << t << "\" file=\"" << file << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
    write_text_file(path_, out.str());
}

}  // namespace fem::io
