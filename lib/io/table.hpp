#pragma once
// Column data files for gnuplot (.dat: whitespace separated, '#' header naming the columns) and
// CSV for spreadsheets. Both are written atomically.
#include <filesystem>
#include <string>
#include <vector>

namespace fem::io {

/// A set of equally long named columns.
struct Table {
    std::vector<std::string> names;
    std::vector<std::vector<double>> columns;

    /// Adds a column; throws std::invalid_argument when its length differs from the others.
    Table& add(std::string name, std::vector<double> values);
    std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
};

/// gnuplot data file: "# name1 name2 ..." then one row per line, 10 significant digits.
void write_dat(const std::filesystem::path& path, const Table& table);
/// Reads a gnuplot data file as write_dat writes it: the first line "# name1 name2 ...", then rows
/// of as many numbers (blank lines and further '#' lines are skipped). Throws InputError naming the
/// file and line for a missing file, a missing header or a malformed row.
Table read_dat(const std::filesystem::path& path);
/// The column named `name`; throws InputError naming the file's columns when there is none.
const std::vector<double>& column(const Table& table, const std::string& name, const std::filesystem::path& path);
/// CSV with a header row.
void write_csv(const std::filesystem::path& path, const Table& table);

}  // namespace fem::io
