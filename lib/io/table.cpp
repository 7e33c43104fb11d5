#include "io/table.hpp"

#include <iomanip>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace fem::io {

Table& Table::add(std::string name, std::vector<double> values) {
    if (!columns.empty() && values.size() != rows())
        throw std::invalid_argument("table column '" + name + "' has " + std::to_string(values.size()) +
                                    " rows, the table has " + std::to_string(rows()));
    names.push_back(std::move(name));
    columns.push_back(std::move(values));
    return *this;
}

namespace {
void write(const std::filesystem::path& path, const Table& table, const char* separator, const char* header_prefix) {
    AtomicFile file(path);
    auto& out = file.stream();
    out << header_prefix;
    for (std::size_t c = 0; c < table.names.size(); ++c) out << (c ? separator : "") << table.names[c];
    out << '\n' << std::setprecision(10);
    for (std::size_t r = 0; r < table.rows(); ++r) {
        for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? separator : "") << table.columns[c][r];
        out << '\n';
    }
    file.commit();
}
}  // namespace

void write_dat(const std::filesystem::path& path, const Table& table) { write(path, table, " ", "# "); }
void write_csv(const std::filesystem::path& path, const Table& table) { write(path, table, ",", ""); }

}  // namespace fem::io
