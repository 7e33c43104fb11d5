// Output writers: atomic files, gnuplot tables, VTU/PVD, HDF5.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/gnuplot.hpp"
#include "io/hdf5.hpp"
#include "io/run_folder.hpp"
#include "io/table.hpp"
#include "io/vtu.hpp"
#include "mesh/mesh.hpp"

namespace fs = std::filesystem;
using namespace fem;

namespace {
fs::path scratch(const std::string& name) {
    auto p = fs::temp_directory_path() / ("fem_io_test_" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}
std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
// Every file and folder name under dir (hidden ones included), relative, sorted.
std::vector<std::string> files_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir)) names.push_back(fs::relative(e.path(), dir).generic_string());
    std::sort(names.begin(), names.end());
    return names;
}
}  // namespace

TEST(AtomicFile, NothingUnderTheFinalNameUntilCommit) {
    const auto dir = scratch("atomic");
    {
        io::AtomicFile f(dir / "a.txt");
        f.stream() << "hello";
        EXPECT_FALSE(fs::exists(dir / "a.txt"));
        f.commit();
    }
    EXPECT_EQ(slurp(dir / "a.txt"), "hello");
    {
        io::AtomicFile f(dir / "b.txt");
        f.stream() << "abandoned";
    }  // destroyed without commit: e.g. an exception on the way
    EXPECT_FALSE(fs::exists(dir / "b.txt"));
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"a.txt"});  // no temporary left behind
    EXPECT_THROW(io::AtomicFile(fs::path("/proc/no/such/dir/x.txt")), InputError);
}

TEST(SafeFileName, KeepsLettersDigitsDashUnderscoreDot) {
    EXPECT_EQ(io::safe_file_name("part[bar].E max/min 1e-3"), "part_bar_.E_max_min_1e-3");
    EXPECT_EQ(io::safe_file_name(""), "");
}

// run_gnuplot hands its variables to gnuplot as they are, whatever the shell or gnuplot would make of
// a quote, a dollar or a back quote in them (a folder named by a user).
TEST(Gnuplot, VariablesArriveVerbatim) {
    const auto dir = scratch("gnuplot it's \"here\"");
    const std::string text = "it's \"$HOME\" `true` \\ done";
    io::write_text_file(dir / "print.gp", "set print out\nprint text\n");
    io::run_gnuplot(dir / "print.gp", {{"out", (dir / "printed.txt").string()}, {"text", text}});
    EXPECT_EQ(slurp(dir / "printed.txt"), text + "\n");
    EXPECT_EQ(io::gnuplot_string("a'b"), "'a''b'");
}

TEST(Table, DatHasHeaderAndRows) {
    const auto dir = scratch("table");
    io::Table t;
    t.add("t", {0, 1, 2}).add("x", {0.5, 1.5, 2.5});
    io::write_dat(dir / "t.dat", t);
    EXPECT_EQ(slurp(dir / "t.dat"), "# t x\n0 0.5\n1 1.5\n2 2.5\n");
    io::write_csv(dir / "t.csv", t);
    EXPECT_EQ(slurp(dir / "t.csv"), "t,x\n0,0.5\n1,1.5\n2,2.5\n");
    EXPECT_THROW(t.add("y", {1.0}), std::invalid_argument);

    // read_dat reads back what write_dat wrote; a malformed file is refused naming file and line.
    const io::Table back = io::read_dat(dir / "t.dat");
    EXPECT_EQ(back.names, t.names);
    EXPECT_EQ(back.columns, t.columns);
    EXPECT_EQ(io::column(back, "x", dir / "t.dat")[2], 2.5);
    EXPECT_THROW(io::column(back, "y", dir / "t.dat"), fem::InputError);
    std::ofstream(dir / "bad.dat") << "# t x\n0 0.5\n1\n";
    try {
        io::read_dat(dir / "bad.dat");
        ADD_FAILURE() << "a short row was accepted";
    } catch (const fem::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.dat:3: 1 values, the header names 2 columns"), std::string::npos) << e.what();
    }
    EXPECT_THROW(io::read_dat(dir / "missing.dat"), fem::InputError);
}

TEST(Vtu, WritesCellsFieldsAndSeries) {
    const auto dir = scratch("vtu");
    Mesh m = box_hex8(1, 1, 1, 2, 1, 1);
    io::VtuData data;
    data.point_fields.push_back({"displacement", 3, std::vector<double>(3 * m.node_count(), 0.1)});
    data.cell_fields.push_back({"von_mises", 1, {1.0, 2.0}});
    io::write_vtu(dir / "box.vtu", m, data);
    const auto text = slurp(dir / "box.vtu");
    EXPECT_NE(text.find("NumberOfPoints=\"12\" NumberOfCells=\"2\""), std::string::npos);
    EXPECT_NE(text.find("format=\"binary\""), std::string::npos);
    EXPECT_NE(text.find("Name=\"von_mises\""), std::string::npos);
    EXPECT_NE(text.find("Name=\"part\""), std::string::npos);
    // A field of the wrong length is refused before anything is written.
    data.cell_fields[0].values = {1.0};
    EXPECT_THROW(io::write_vtu(dir / "bad.vtu", m, data), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir / "bad.vtu"));

    data.cell_fields.clear();
    io::PvdSeries series(dir / "run.pvd");
    series.add(0.0, m, data);
    series.add(0.5, m, data);
    EXPECT_TRUE(fs::exists(dir / "run_0001.vtu"));
    EXPECT_NE(slurp(dir / "run.pvd").find("timestep=\"0.5\" file=\"run_0001.vtu\""), std::string::npos);
}

TEST(Hdf5, RoundTripAndAtomic) {
    const auto dir = scratch("h5");
    {
        io::H5Writer h5(dir / "r.h5");
        h5.write("history/tip/time", std::vector<double>{0, 0.1, 0.2});
        Eigen::MatrixXd modes(2, 3);
        modes << 1, 2, 3, 4, 5, 6;
        h5.write("modes/shapes", modes);
        h5.write_ints("mesh/ids", {7, 8});
        h5.attribute("modes/shapes", "unit", "m");
        h5.attribute("/", "alpha", 7.5);
        EXPECT_FALSE(fs::exists(dir / "r.h5"));
        h5.commit();
    }
    const auto shapes = io::read_h5_matrix(dir / "r.h5", "modes/shapes");
    ASSERT_EQ(shapes.rows(), 2);
    ASSERT_EQ(shapes.cols(), 3);
    EXPECT_EQ(shapes(1, 2), 6.0);
    const auto t = io::read_h5_matrix(dir / "r.h5", "history/tip/time");
    EXPECT_EQ(t.rows(), 3);
    EXPECT_DOUBLE_EQ(t(2, 0), 0.2);
    EXPECT_THROW(io::read_h5_matrix(dir / "r.h5", "nope"), InputError);
}

TEST(RunFolder, ReplacesThePreviousSetAsAUnit) {
    const auto dir = scratch("run_folder") / "out";
    {  // first run: three files (one in a subfolder)
        io::RunFolder run(dir, "test");
        EXPECT_TRUE(fs::exists(dir / ".lock"));
        io::write_text_file(run.staging() / "a.txt", "1");
        io::write_text_file(run.staging() / "b.txt", "1");
        io::write_text_file(run.staging() / "sub" / "c.txt", "1");
        EXPECT_FALSE(fs::exists(dir / "a.txt"));  // nothing under a final name before commit
        run.commit();
    }
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.txt", "b.txt", "manifest.txt", "sub", "sub/c.txt"}));
    EXPECT_EQ(slurp(dir / "manifest.txt").substr(slurp(dir / "manifest.txt").find('\n') + 1), "a.txt\nb.txt\nsub/c.txt\n");
    io::write_text_file(dir / "mine.txt", "a user's own file");
    {  // a run that fails (no commit): the previous set stays as it was
        io::RunFolder run(dir, "test");
        io::write_text_file(run.staging() / "a.txt", "half");
    }
    EXPECT_EQ(slurp(dir / "a.txt"), "1");
    EXPECT_EQ(files_in(dir).size(), 6u);
    {  // second run writes only a.txt: b.txt and sub/c.txt were the previous run's and go
        io::RunFolder run(dir, "test");
        io::write_text_file(run.staging() / "a.txt", "2");
        run.commit();
    }
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.txt", "manifest.txt", "mine.txt"}));
    EXPECT_EQ(slurp(dir / "a.txt"), "2");
}

TEST(RunFolder, RefusesAConcurrentRunAndCleansKilledRuns) {
    const auto dir = scratch("run_folder_lock");
    {
        io::RunFolder first(dir, "first");
        try {
            io::RunFolder second(dir, "second");
            ADD_FAILURE() << "two runs share a folder";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("is in use by another run (first pid"), std::string::npos) << e.what();
        }
    }
    // What a killed run leaves: its staging folder and a temporary; the next run removes both.
    fs::create_directories(dir / ".run-999999-1");
    io::write_text_file(dir / ".run-999999-1" / "modes.h5", "half");
    io::write_text_file(dir / "frequencies.csv.999999-0.partial", "half");
    {
        io::RunFolder run(dir, "test");
        EXPECT_FALSE(fs::exists(dir / ".run-999999-1"));
        EXPECT_FALSE(fs::exists(dir / "frequencies.csv.999999-0.partial"));
    }
    EXPECT_TRUE(files_in(dir).empty());
}

TEST(RunFolder, AResumedRunAdoptsTheKilledRunsStagingFolder) {
    const auto dir = scratch("run_folder_adopt");
    // Two killed runs' staging folders (the newer one is the run to resume) and a temporary.
    fs::create_directories(dir / ".run-999998-1");
    io::write_text_file(dir / ".run-999998-1" / "old-restart-1.h5", "older");
    fs::last_write_time(dir / ".run-999998-1", fs::file_time_type::clock::now() - std::chrono::hours(1));
    fs::create_directories(dir / ".run-999999-2");
    io::write_text_file(dir / ".run-999999-2" / "bar-restart-7.h5", "dump");
    io::write_text_file(dir / ".run-999999-2" / "results_0000.vtu.999999-0.partial", "half");
    {  // adopted, then failing again: kept for the next resume
        io::RunFolder run(dir, "test", io::RunFolder::Leftovers::adopt);
        EXPECT_TRUE(run.adopted());
        EXPECT_EQ(run.staging(), dir / ".run-999999-2");
        EXPECT_EQ(slurp(run.staging() / "bar-restart-7.h5"), "dump");
        EXPECT_FALSE(fs::exists(dir / ".run-999998-1"));
        EXPECT_FALSE(fs::exists(dir / ".run-999999-2" / "results_0000.vtu.999999-0.partial"));
    }
    EXPECT_TRUE(fs::exists(dir / ".run-999999-2" / "bar-restart-7.h5"));
    {  // adopted and completed: the killed run's files and the resumed run's are one set
        io::RunFolder run(dir, "test", io::RunFolder::Leftovers::adopt);
        ASSERT_TRUE(run.adopted());
        io::write_text_file(run.staging() / "bar-restart-9.h5", "dump 2");
        run.commit();
    }
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"bar-restart-7.h5", "bar-restart-9.h5", "manifest.txt"}));
    {  // nothing to adopt: a fresh staging folder
        io::RunFolder run(dir, "test", io::RunFolder::Leftovers::adopt);
        EXPECT_FALSE(run.adopted());
    }
}

TEST(RunFolder, ACommitKilledOnTheWayIsRepairedByTheNextRun) {
    const auto dir = scratch("run_folder_killed_commit");
    {
        io::RunFolder run(dir, "test");
        io::write_text_file(run.staging() / "a.txt", "1");
        io::write_text_file(run.staging() / "b.txt", "1");
        run.commit();
    }
    EXPECT_FALSE(fs::exists(dir / io::RunFolder::pending_name));
    // What a run killed in commit() leaves: its list, c.txt already moved into place, b2.txt staged.
    io::write_text_file(dir / io::RunFolder::pending_name, "# staging folder .run-999999-3\nb2.txt\nc.txt\n");
    io::write_text_file(dir / "c.txt", "2");
    fs::create_directories(dir / ".run-999999-3");
    io::write_text_file(dir / ".run-999999-3" / "b2.txt", "2");
    {  // resumed: c.txt goes back to the adopted staging folder, which is whole again
        io::RunFolder run(dir, "test", io::RunFolder::Leftovers::adopt);
        ASSERT_TRUE(run.adopted());
        EXPECT_EQ(slurp(run.staging() / "c.txt"), "2");
        EXPECT_FALSE(fs::exists(dir / "c.txt"));
        io::write_text_file(dir / "c.txt", "2");  // as if the resume had not happened (the run failed)
    }
    {  // a fresh run that writes only a.txt: b.txt (previous set) and c.txt (the killed commit's) are stale
        io::RunFolder run(dir, "test");
        io::write_text_file(run.staging() / "a.txt", "3");
        run.commit();
    }
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.txt", "manifest.txt"}));
}

TEST(RunFolder, AnUnwritableFolderIsRefusedBeforeTheRun) {
    const auto dir = scratch("run_folder_bad");
    io::write_text_file(dir / "file", "x");
    EXPECT_THROW(io::RunFolder(dir / "file", "test"), InputError);           // a file, not a folder
    EXPECT_THROW(io::RunFolder(dir / "file" / "sub", "test"), InputError);   // cannot be created
    EXPECT_THROW(io::RunFolder("/proc/fem-no-such-folder", "test"), InputError);
    {  // a run that fails leaves no folder it created
        io::RunFolder run(dir / "new", "test");
    }
    EXPECT_FALSE(fs::exists(dir / "new"));
}

TEST(H5Writer, IdenticalContentGivesIdenticalBytes) {
    // No object time stamps: two files written at different times are byte for byte the same.
    const auto dir = scratch("h5_bytes");
    for (const char* name : {"a.h5", "b.h5"}) {
        io::H5Writer h5(dir / name);
        h5.write("group/values", std::vector<double>{1, 2, 3});
        h5.write("matrix", Eigen::MatrixXd::Identity(3, 2));
        h5.write_ints("ids", {4, 5});
        h5.attribute("/", "program", "test");
        h5.attribute("group/values", "unit", 1.0);
        h5.commit();
        if (std::string(name) == "a.h5") std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    }
    EXPECT_EQ(slurp(dir / "a.h5"), slurp(dir / "b.h5"));
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.h5", "b.h5"}));
}
