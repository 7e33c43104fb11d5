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
/// CSV with a header row.
void write_csv(const std::filesystem::path& path, const Table& table);

}  // namespace fem::io
