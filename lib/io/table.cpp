#include "io/table.hpp"

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "core/error.hpp"

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

Table read_dat(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError("data file '" + path.string() + "' not found");
    std::string line;
    int line_no = 0;
    Table table;
    while (std::getline(in, line)) {
        ++line_no;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos) continue;
        std::istringstream words(line.substr(first));
        if (line[first] == '#') {
            if (!table.names.empty()) continue;
            words.get();
            for (std::string name; words >> name;) table.names.push_back(name);
            table.columns.resize(table.names.size());
            continue;
        }
        if (table.names.empty())
            throw InputError(path.string() + ":" + std::to_string(line_no) + ": data before the '# <column names>' header");
        std::vector<double> row;
        for (std::string word; words >> word;) {
            char* end = nullptr;
            const double v = std::strtod(word.c_str(), &end);
            if (end == word.c_str() || *end != '\0')
                throw InputError(path.string() + ":" + std::to_string(line_no) + ": '" + word + "' is not a number");
            row.push_back(v);
        }
        if (row.size() != table.names.size())
            throw InputError(path.string() + ":" + std::to_string(line_no) + ": " + std::to_string(row.size()) +
                             " values, the header names " + std::to_string(table.names.size()) + " columns");
        for (std::size_t c = 0; c < row.size(); ++c) table.columns[c].push_back(row[c]);
    }
    if (table.names.empty()) throw InputError(path.string() + ": no '# <column names>' header line");
    return table;
}

const std::vector<double>& column(const Table& table, const std::string& name, const std::filesystem::path& path) {
    for (std::size_t c = 0; c < table.names.size(); ++c)
        if (table.names[c] == name) return table.columns[c];
    std::string names;
    for (const auto& n : table.names) names += (names.empty() ? "" : ", ") + n;
    throw InputError(path.string() + ": no column '" + name + "' (it has " + names + ")");
}

}  // namespace fem::io
