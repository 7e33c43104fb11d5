#include "io/vtu.hpp"

#include <cstdint>
#include <cstring>
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
        case ElementShape::Hex20: return 25;   // VTK_QUADRATIC_HEXAHEDRON (same node order as ours)
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

// VTU "binary" inline data: base64 of a UInt64 byte count followed by the raw little-endian
// values. About 3x smaller and much faster to write than ASCII for the meshes of the studies.
void base64(std::ostream& out, const unsigned char* data, std::size_t n) {
    static constexpr char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string line;
    line.reserve((n + 2) / 3 * 4);
    for (std::size_t i = 0; i < n; i += 3) {
        const unsigned b0 = data[i], b1 = i + 1 < n ? data[i + 1] : 0, b2 = i + 2 < n ? data[i + 2] : 0;
        line += table[b0 >> 2];
        line += table[((b0 & 3) << 4) | (b1 >> 4)];
        line += i + 1 < n ? table[((b1 & 15) << 2) | (b2 >> 6)] : '=';
        line += i + 2 < n ? table[b2 & 63] : '=';
    }
    out << line;
}

template <class T>
void data_array(std::ostream& out, const char* type, const std::string& name, int components, const std::vector<T>& values) {
    out << "        <DataArray type=\"" << type << "\"";
    if (!name.empty()) out << " Name=\"" << name << "\"";
    if (components > 1) out << " NumberOfComponents=\"" << components << "\"";
    out << " format=\"binary\">\n          ";
    std::vector<unsigned char> bytes(sizeof(std::uint64_t) + values.size() * sizeof(T));
    const std::uint64_t size = values.size() * sizeof(T);
    std::memcpy(bytes.data(), &size, sizeof size);
    if (!values.empty()) std::memcpy(bytes.data() + sizeof size, values.data(), size);
    base64(out, bytes.data(), bytes.size());
    out << "\n        </DataArray>\n";
}

void check_field(const Field& f, std::size_t expected_count, const char* where) {
    if (f.values.size() != expected_count * f.components)
        throw std::invalid_argument(std::string("VTU ") + where + " field '" + f.name + "' has " +
                                    std::to_string(f.values.size()) + " values, expected " +
                                    std::to_string(expected_count * f.components));
}

void write_field(std::ostream& out, const Field& f) {
    // Fields are for viewing: single precision is plenty and halves the file.
    data_array(out, "Float32", f.name, f.components, std::vector<float>(f.values.begin(), f.values.end()));
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const Mesh& mesh, const VtuData& data, std::span<const Vec3> x) {
    if (x.empty()) x = mesh.nodes;
    if (static_cast<int>(x.size()) != mesh.node_count())
        throw std::invalid_argument("VTU coordinates do not match the mesh's node count");
    // Check every field before anything is written.
    const int cells = mesh.element_count();
    for (const auto& f : data.point_fields) check_field(f, mesh.node_count(), "point");
    for (const auto& f : data.cell_fields) check_field(f, cells, "cell");
    AtomicFile file(path);
    auto& out = file.stream();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
           " header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\""
        << mesh.node_count() << "\" NumberOfCells=\"" << cells << "\">\n      <Points>\n";
    std::vector<double> points;
    points.reserve(3 * x.size());
    for (const auto& p : x) points.insert(points.end(), {p.x(), p.y(), p.z()});
    data_array(out, "Float64", "", 3, points);
    out << "      </Points>\n      <Cells>\n";
    std::vector<std::int64_t> connectivity, offsets;
    std::vector<std::uint8_t> types;
    for (const auto& b : mesh.blocks)
        for (int e = 0; e < b.size(); ++e) {
            auto conn = b.element(e);
            for (int k = 0; k < b.nodes_per_element(); ++k) connectivity.push_back(conn[vtk_node(b.shape, k)]);
            offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
            types.push_back(static_cast<std::uint8_t>(vtk_cell_type(b.shape)));
        }
    data_array(out, "Int64", "connectivity", 1, connectivity);
    data_array(out, "Int64", "offsets", 1, offsets);
    data_array(out, "UInt8", "types", 1, types);
    out << "      </Cells>\n      <PointData>\n";
    for (const auto& f : data.point_fields) write_field(out, f);
    out << "      </PointData>\n      <CellData>\n";
    Field part{"part", 1, {}};
    for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b) part.values.insert(part.values.end(), mesh.blocks[b].size(), b);
    write_field(out, part);
    for (const auto& f : data.cell_fields) write_field(out, f);
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
