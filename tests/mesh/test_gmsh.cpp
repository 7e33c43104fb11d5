// The Gmsh reader: meshes made with the Gmsh API, written as .msh 2.2 and 4.1 (ASCII and binary),
// read back and compared with the in-memory model and with exact geometry; hand-written files for
// node order and errors.
#include <gtest/gtest.h>
#include <gmsh.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <fstream>

#include "core/error.hpp"
#include "mesh/finger.hpp"
#include "mesh/gmsh.hpp"

using namespace fem;
namespace fs = std::filesystem;

namespace {

// A scratch directory removed at the end of the test.
struct TempDir {
    fs::path path;
    TempDir() {
        static std::atomic<int> counter{0};
        path = fs::temp_directory_path() / ("fem_test_mesh_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    fs::path file(const std::string& name) const { return path / name; }
};

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// Writes the current Gmsh model in the given format.
void write_model(const fs::path& p, double version, bool binary) {
    gmsh::option::setNumber("Mesh.MshFileVersion", version);
    gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
    gmsh::write(p.string());
}

// 1 x 2 x 3 box of tetrahedra (order 1 or 2), physical volume "solid" and surface "bottom" (z = 0).
void make_box_model(int order) {
    gmsh::clear();
    gmsh::model::add("box");
    const int v = gmsh::model::occ::addBox(0, 0, 0, 1, 2, 3);
    gmsh::model::occ::synchronize();
    gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {v}), "solid");
    gmsh::vectorpair bottom;
    gmsh::model::getEntitiesInBoundingBox(-1, -1, -1e-6, 2, 3, 1e-6, bottom, 2);
    ASSERT_EQ(bottom.size(), 1u);
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {bottom[0].second}), "bottom");
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.7);
    gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);
    gmsh::model::mesh::generate(3);
    if (order == 2) gmsh::model::mesh::setOrder(2);
}

std::vector<std::array<double, 3>> coordinates(const Mesh& m) {
    std::vector<std::array<double, 3>> c;
    for (const auto& x : m.nodes) c.push_back({x.x(), x.y(), x.z()});
    return c;
}

}  // namespace

// The round trip in all four encodings: the same nodes, elements and node sets as the model in
// memory, and the exact volume of the box.
TEST(ReadGmsh, RoundTripAllFormats) {
    TempDir dir;
    struct Format { double version; bool binary; const char* name; };
    const Format formats[] = {{2.2, false, "v22_ascii.msh"}, {2.2, true, "v22_binary.msh"},
                              {4.1, false, "v41_ascii.msh"}, {4.1, true, "v41_binary.msh"}};
    Mesh expected;
    {
        GmshSession session;
        make_box_model(1);
        expected = mesh_from_gmsh_model();
        for (const auto& f : formats) write_model(dir.file(f.name), f.version, f.binary);
        gmsh::clear();
    }
    ASSERT_EQ(expected.blocks.size(), 1u);  // "bottom" is a boundary face: a node set, not a block
    EXPECT_EQ(expected.blocks[0].part, "solid");
    EXPECT_EQ(expected.blocks[0].shape, ElementShape::Tet4);
    EXPECT_THROW(expected.blocks_of_part("bottom"), InputError);
    for (const auto& f : formats) {
        SCOPED_TRACE(f.name);
        const Mesh m = read_gmsh(dir.file(f.name));
        EXPECT_EQ(m.node_count(), expected.node_count());
        EXPECT_EQ(m.element_count(), expected.element_count());
        ASSERT_EQ(m.blocks.size(), 1u);
        EXPECT_EQ(m.blocks[0].part, "solid");
        EXPECT_EQ(m.blocks[0].shape, ElementShape::Tet4);
        EXPECT_EQ(m.blocks[0].connectivity, expected.blocks[0].connectivity);
        // Binary files carry the doubles exactly; ASCII ones with 16 significant digits (Gmsh's
        // %.16g): coordinates up to 3 are within 3 * 10^-15 (half a unit in the 16th digit, x10 margin).
        // Gmsh keeps node tags in the file, so both meshes number their nodes alike.
        const auto got = coordinates(m), want = coordinates(expected);
        ASSERT_EQ(got.size(), want.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < got.size(); ++i)
            for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(got[i][d] - want[i][d]));
        if (f.binary) EXPECT_EQ(worst, 0.0);
        else EXPECT_LT(worst, 3e-15);
        EXPECT_NEAR(finger::mesh_quality(m).volume, 6.0, 1e-12);           // a box is meshed exactly
        ASSERT_EQ(m.node_set("bottom").size(), expected.node_set("bottom").size());
        for (int n : m.node_set("bottom")) EXPECT_EQ(m.nodes[n].z(), 0.0);
        // Contiguous 0-based numbering: every node is used.
        std::vector<bool> used(m.node_count(), false);
        for (int n : m.blocks[0].connectivity) used[n] = true;
        EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
    }
}

// Straight-sided 10-node tetrahedra: every mid-edge node is the midpoint of the edge our convention
// (element_shape.hpp: 01, 12, 20, 03, 23, 13) assigns to it. With VTK's order (13 before 23) nodes 8
// and 9 would fail.
TEST(ReadGmsh, Tet10MidEdgeOrder) {
    TempDir dir;
    {
        GmshSession session;
        make_box_model(2);
        write_model(dir.file("tet10.msh"), 4.1, false);
        gmsh::clear();
    }
    const Mesh m = read_gmsh(dir.file("tet10.msh"));
    ASSERT_EQ(m.blocks.size(), 1u);
    ASSERT_EQ(m.blocks[0].shape, ElementShape::Tet10);
    const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
    for (int e = 0; e < m.blocks[0].size(); ++e) {
        const auto x = m.element_coordinates(0, e);
        for (int k = 0; k < 6; ++k)
            ASSERT_LT((x[4 + k] - 0.5 * (x[edge[k][0]] + x[edge[k][1]])).norm(), 1e-12) << "element " << e << " node " << 4 + k;
    }
    const auto q = finger::mesh_quality(m);
    EXPECT_NEAR(q.volume, 6.0, 1e-12);
    EXPECT_NEAR(q.min_jacobian_ratio, 1.0, 1e-9);  // straight sides: the quadratic map is affine
}

// Serendipity quadrilaterals (Gmsh type 16) in format 2.2: mid-edge nodes 01, 12, 23, 30.
TEST(ReadGmsh, Quad8Plate) {
    TempDir dir;
    {
        GmshSession session;
        gmsh::clear();
        const int s = gmsh::model::occ::addRectangle(0, 0, 0, 2, 1);
        gmsh::model::occ::synchronize();
        gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {s}), "plate");
        gmsh::option::setNumber("Mesh.MeshSizeMax", 0.3);
        gmsh::option::setNumber("Mesh.RecombineAll", 1);
        gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);
        gmsh::model::mesh::generate(2);
        gmsh::model::mesh::setOrder(2);
        write_model(dir.file("quad8.msh"), 2.2, false);
        gmsh::clear();
    }
    const Mesh m = read_gmsh(dir.file("quad8.msh"));
    ASSERT_EQ(m.blocks.size(), 1u);
    ASSERT_EQ(m.blocks[0].shape, ElementShape::Quad8);
    EXPECT_EQ(m.blocks[0].part, "plate");
    double area = 0.0;
    for (int e = 0; e < m.blocks[0].size(); ++e) {
        const auto x = m.element_coordinates(0, e);
        for (int k = 0; k < 4; ++k) {
            area += 0.5 * (x[k].x() * x[(k + 1) % 4].y() - x[(k + 1) % 4].x() * x[k].y());
            EXPECT_LT((x[4 + k] - 0.5 * (x[k] + x[(k + 1) % 4])).norm(), 1e-12);
        }
    }
    EXPECT_NEAR(area, 2.0, 1e-12);
    // The plate is a 2D model: its physical surface is a block and a node set.
    EXPECT_EQ(m.node_set("plate").size(), static_cast<std::size_t>(m.node_count()));
}

// Hexahedra (transfinite, recombined) plus a free-standing beam and point mass: the curve and the
// point are not on the solid's boundary, so they are blocks too.
TEST(ReadGmsh, HexBeamAndPointBlocks) {
    TempDir dir;
    {
        GmshSession session;
        gmsh::clear();
        const int v = gmsh::model::occ::addBox(0, 0, 0, 1, 1, 2);
        const int p0 = gmsh::model::occ::addPoint(3, 0, 0), p1 = gmsh::model::occ::addPoint(3, 0, 1);
        const int line = gmsh::model::occ::addLine(p0, p1);
        const int mass = gmsh::model::occ::addPoint(5, 5, 5);
        gmsh::model::occ::synchronize();
        gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {v}), "brick");
        gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, {line}), "beam");
        gmsh::model::setPhysicalName(0, gmsh::model::addPhysicalGroup(0, {mass}), "mass");
        gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
        gmsh::model::mesh::setTransfiniteAutomatic();  // every entity: recombined, so hexahedra
        gmsh::model::mesh::setTransfiniteCurve(line, 6);
        gmsh::model::mesh::generate(3);
        write_model(dir.file("hex.msh"), 4.1, true);
        gmsh::clear();
    }
    const Mesh m = read_gmsh(dir.file("hex.msh"));
    const auto brick = m.blocks[m.blocks_of_part("brick").at(0)];
    const auto beam = m.blocks[m.blocks_of_part("beam").at(0)];
    const auto mass = m.blocks[m.blocks_of_part("mass").at(0)];
    EXPECT_EQ(brick.shape, ElementShape::Hex8);
    EXPECT_EQ(beam.shape, ElementShape::Beam2);
    EXPECT_EQ(beam.size(), 5);
    EXPECT_EQ(mass.shape, ElementShape::Point1);
    EXPECT_EQ(mass.size(), 1);
    const auto q = finger::mesh_quality(m);
    EXPECT_NEAR(q.volume, 2.0, 1e-12);
    EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-9);  // a transfinite box is made of bricks
    EXPECT_EQ(m.node_set("beam").size(), 6u);
    EXPECT_EQ(m.node_set("mass").size(), 1u);
}

// A hand-written 2.2 file: the reader keeps Gmsh's node order and renumbers sparse tags.
TEST(ReadGmsh, HandWrittenTet10KeepsNodeOrder) {
    TempDir dir;
    write_text(dir.file("one.msh"),
               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
               "$PhysicalNames\n1\n3 7 \"rubber\"\n$EndPhysicalNames\n"
               "$Nodes\n10\n"
               "10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n"
               "50 0.5 0 0\n60 0.5 0.5 0\n70 0 0.5 0\n80 0 0 0.5\n90 0 0.5 0.5\n100 0.5 0 0.5\n"
               "$EndNodes\n"
               "$Elements\n1\n1 11 2 7 1 10 20 30 40 50 60 70 80 90 100\n$EndElements\n");
    const Mesh m = read_gmsh(dir.file("one.msh"));
    ASSERT_EQ(m.node_count(), 10);
    ASSERT_EQ(m.blocks.size(), 1u);
    EXPECT_EQ(m.blocks[0].part, "rubber");
    EXPECT_EQ(m.blocks[0].shape, ElementShape::Tet10);
    for (int k = 0; k < 10; ++k) EXPECT_EQ(m.blocks[0].connectivity[k], k);  // tags 10..100 -> 0..9 in order
    EXPECT_EQ(m.nodes[8], Vec3(0, 0.5, 0.5));                                  // node 8: edge 23
    EXPECT_NEAR(finger::mesh_quality(m).volume, 1.0 / 6.0, 1e-14);
}

TEST(ReadGmsh, ErrorsNameTheFile) {
    TempDir dir;
    auto expect_error = [](const fs::path& p, const std::string& needle) {
        try {
            read_gmsh(p);
            ADD_FAILURE() << "no error for " << p;
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(p.filename().string()), std::string::npos) << what;
            EXPECT_NE(what.find(needle), std::string::npos) << what;
        }
    };
    expect_error(dir.file("missing.msh"), "does not exist");
    write_text(dir.file("bad.msh"), "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\ngarbage\n");
    expect_error(dir.file("bad.msh"), "malformed");
    write_text(dir.file("empty.msh"), "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
    expect_error(dir.file("empty.msh"), "no elements");
    write_text(dir.file("mesh.geo"), "Point(1) = {0, 0, 0};\n");
    expect_error(dir.file("mesh.geo"), ".msh");
    // An inverted tetrahedron (corners 1 and 2 swapped) fails validation.
    write_text(dir.file("inverted.msh"),
               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
               "$Elements\n1\n1 4 2 1 1 1 3 2 4\n$EndElements\n");
    expect_error(dir.file("inverted.msh"), "inverted");
    // Second-order triangles as a free-standing surface: a type the library has no element for.
    write_text(dir.file("tri6.msh"),
               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0.5 0 0\n5 0.5 0.5 0\n6 0 0.5 0\n"
               "$EndNodes\n$Elements\n1\n1 9 2 1 1 1 2 3 4 5 6\n$EndElements\n");
    expect_error(dir.file("tri6.msh"), "Triangle 6");
}

// A read that Gmsh fails midway must not spoil later reads in the same process and session (Gmsh
// 4.8's open() kept a "busy" lock after such a failure, and every later file read as empty; found by
// tests/fuzz/fuzz_gmsh, which keeps one session for its whole run).
TEST(ReadGmsh, AFailedReadDoesNotSpoilTheNextOne) {
    TempDir dir;
    const std::string tet = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
                            "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n";
    write_text(dir.file("tet.msh"), tet);
    write_text(dir.file("short.msh"), "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                                      "4 0 0 1\n$EndNodes\n$Elements\n1\n1 4 2 1 1 1 2\n$EndElements\n");
    write_text(dir.file("twice.msh"), "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                                      "4 0 0 1\n4 0 0 2\n$EndNodes\n$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n");
    GmshSession outer;  // as a program that reads several files would hold
    EXPECT_EQ(read_gmsh(dir.file("tet.msh")).element_count(), 1);
    EXPECT_THROW(read_gmsh(dir.file("short.msh")), InputError);
    EXPECT_EQ(read_gmsh(dir.file("tet.msh")).element_count(), 1);
    // One reader process reads them all: Gmsh's log of one file must not reach the next one's message.
    EXPECT_THROW(read_gmsh(dir.file("twice.msh")), InputError);
    try {
        read_gmsh(dir.file("short.msh"));
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find("uplicate"), std::string::npos) << e.what();
    }
    EXPECT_EQ(read_gmsh(dir.file("tet.msh")).element_count(), 1);
}

// A file on which libgmsh 4.8 itself crashes (SIGSEGV in GModel::_associateEntityWithMeshVertices,
// called from _readMSH2; found by tests/fuzz/fuzz_gmsh, also in its corpus): Gmsh reads it in a child
// process, whose death becomes an InputError naming the file and the signal; the child is reaped,
// and this process reads the next file as before.
// The crash itself is deterministic: the quad's fourth node, 6, is not among the 5 nodes $Nodes
// announces, so the element's MVertex* is null and Gmsh reads 0x38 bytes past it (gdb on gmsh 4.8.4:
// `cmpq $0x0,0x38(%rax)` with rax = 0), an address never mapped whatever the layout (ASLR): SIGSEGV
// in every run (2026-12-02: 300 of 300 runs of this test in the Release build, 200 of them in two
// parallel streams, load 7-9; 60 of 60 under ASan + UBSan + LSan, two streams, load 8-11). The one
// failure seen before (two test streams, message not kept) was not reproduced. The reader reports
// every fatal signal alike (reply_of_reader), so the test asks for that form, with any signal, rather
// than for signal 11, and names any other outcome (a different exception) in its failure message.
TEST(ReadGmsh, ACrashInsideGmshIsAnInputError) {
    TempDir dir;
    write_text(dir.file("crash.msh"),
               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNamas\n2\n2 2 t\"oor\"\x8e\n3 1 \"beam0\n"
               "$EndPhyswcalNames\n$Nodes\n5\n1 0 0 0\n2 0.4 0 0\n3 0.4 0.05 0\n4 0 0.05 0\n5 0 0 0.05\n"
               "6 0.4 0 0.05\n$EndNodes\n$Elements\n2\n1 3 2 2 1 1 2 5 6\n2  1 2 5 4\n2 3 2 1 1 2 3 6 5\n3 nts\n");
    try {
        read_gmsh(dir.file("crash.msh"));
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what(), head = "Gmsh crashed reading '" + dir.file("crash.msh").string() + "' (signal ",
                          tail = "): the file is malformed";
        EXPECT_EQ(message.rfind(head, 0), 0u) << message;
        EXPECT_TRUE(message.size() > head.size() + tail.size() && message.ends_with(tail)) << message;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not an InputError: " << e.what();
    }
    errno = 0;
    EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);  // no child left behind, not even a zombie
    EXPECT_EQ(errno, ECHILD);
    write_text(dir.file("tet.msh"), "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                                    "4 0 0 1\n$EndNodes\n$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n");
    EXPECT_EQ(read_gmsh(dir.file("tet.msh")).element_count(), 1);
}

// A 1 kB binary MSH 4.1 file on which libgmsh 4.8 spends minutes (a huge count; found by
// tests/fuzz/fuzz_gmsh, also in its corpus): past the time limit the reader process is killed and the
// file refused. (Limit shortened for the test; the default is 30 s + 10 s/MB.)
TEST(ReadGmsh, AReadThatTakesTooLongIsAnInputError) {
    const fs::path slow = "tests/fuzz/corpus/gmsh/timeout-msh4-binary-count.msh";
    ASSERT_TRUE(fs::exists(slow));
    set_gmsh_read_time_limit(0.5, 0);
    try {
        read_gmsh(slow);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("timeout-msh4-binary-count.msh' is malformed: Gmsh did not finish reading it in "
                                             "0.5 s (1171 bytes"),
                  std::string::npos)
            << e.what();
    }
    errno = 0;
    EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);  // the reader was killed and reaped
    EXPECT_EQ(errno, ECHILD);
    set_gmsh_read_time_limit(30, 10);
}

#ifdef _OPENMP
// Gmsh sets the calling thread's OpenMP thread count (omp_set_num_threads at initialize, on
// General.NumThreads, in every mesh generation); a session gives the caller's back when it ends,
// nested sessions included, so a program that meshes and then solves keeps its threads.
TEST(GmshSession, LeavesTheCallersThreadCountAlone) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(3);  // not Gmsh's 1, and not the default of this machine's 2 cores
    int inside = 0;
    {
        GmshSession outer;
        {
            GmshSession inner;  // as chicken_mesh inside a program's own session
            make_box_model(2);
            const Mesh m = mesh_from_gmsh_model("box");
            EXPECT_GT(m.element_count(), 0);
            inside = omp_get_max_threads();
            gmsh::clear();
        }
        gmsh::model::add("again");
        gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
        gmsh::model::occ::synchronize();
        gmsh::model::mesh::generate(3);
        gmsh::clear();
    }
    EXPECT_EQ(omp_get_max_threads(), 3);
    // What the session guards against (recorded, not required: a later Gmsh may leave it alone).
    RecordProperty("threads_inside_the_session", inside);
    {
        GmshSession alone;  // initialize and finalize only
    }
    EXPECT_EQ(omp_get_max_threads(), 3);
    omp_set_num_threads(saved);
}
#endif

namespace {
// Is a library whose file name contains `name` mapped into this process (/proc/self/maps)?
bool library_mapped(const std::string& name) {
    std::ifstream maps("/proc/self/maps");
    for (std::string line; std::getline(maps, line);)
        if (line.find(name) != std::string::npos) return true;
    return false;
}
// Taken while the program starts (static initialisation, after the loader has mapped every library
// the program needs and before any test runs), so that the order the tests run in does not matter.
const bool gmsh_mapped_at_start = library_mapped("libgmsh.so");
}  // namespace

// No program links libgmsh (its start costs 0.12 s: mesh/gmsh_api.hpp); the first Gmsh call loads it
// through the plugin, and Gmsh's exceptions reach the caller as from Gmsh's own API.
TEST(GmshPlugin, GmshIsLoadedByTheFirstGmshCallNotAtStart) {
    EXPECT_FALSE(gmsh_mapped_at_start) << "a program of the project links libgmsh again";
    {
        GmshSession session;
        EXPECT_TRUE(library_mapped("libgmsh.so"));
        EXPECT_TRUE(library_mapped("libfem_gmsh.so"));
        gmsh::model::add("plugin");
        EXPECT_EQ(gmsh::model::occ::addBox(0, 0, 0, 1, 2, 3), 1);  // a return value passed back
        gmsh::model::occ::synchronize();
        double volume = 0;
        gmsh::model::occ::getMass(3, 1, volume);  // an output argument
        EXPECT_NEAR(volume, 6.0, 1e-12);
        // Gmsh's API throws its last error message as a std::string (what gmsh.cpp catches).
        EXPECT_THROW(gmsh::model::occ::getMass(3, 99, volume), std::string);
        gmsh::clear();
    }
}
