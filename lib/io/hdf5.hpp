#pragma once
// HDF5 output (time histories, modes, densities), readable with h5py or h5dump. Datasets are named
// by slash paths ("history/tip/displacement"); groups are created on the way. The file is written
// under a temporary name and renamed on commit(), so no half-written file is left under its name.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace fem::io {

class H5Writer {
public:
    explicit H5Writer(std::filesystem::path path);
    ~H5Writer();
    H5Writer(const H5Writer&) = delete;
    H5Writer& operator=(const H5Writer&) = delete;

    /// A 1-D dataset of doubles.
    void write(const std::string& dataset, const std::vector<double>& values);
    /// A 2-D dataset (rows x cols, row-major in the file as h5py shows it).
    void write(const std::string& dataset, const Eigen::MatrixXd& values);
    /// A 1-D dataset of integers.
    void write_ints(const std::string& dataset, const std::vector<long long>& values);
    /// String and number attributes on a dataset or group ("/" for the file).
    void attribute(const std::string& object, const std::string& name, const std::string& value);
    void attribute(const std::string& object, const std::string& name, double value);

    void commit();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Reads an HDF5 file written by H5Writer (restart files, tests). Every reading error is an
/// InputError naming the file and the dataset or attribute.
class H5Reader {
public:
    explicit H5Reader(std::filesystem::path path);
    ~H5Reader();
    H5Reader(const H5Reader&) = delete;
    H5Reader& operator=(const H5Reader&) = delete;

    const std::filesystem::path& path() const { return path_; }
    /// True when the dataset or group exists.
    bool has(const std::string& name) const;
    std::vector<double> read(const std::string& dataset) const;
    Eigen::MatrixXd read_matrix(const std::string& dataset) const;
    std::vector<long long> read_ints(const std::string& dataset) const;
    /// Attributes on a dataset or group ("/" for the file).
    double attribute_number(const std::string& object, const std::string& name) const;
    std::string attribute_string(const std::string& object, const std::string& name) const;

private:
    struct Impl;
    std::filesystem::path path_;
    std::unique_ptr<Impl> impl_;
};

/// Reads a 1-D or 2-D double dataset back (for tests and post-processing).
Eigen::MatrixXd read_h5_matrix(const std::filesystem::path& path, const std::string& dataset);

}  // namespace fem::io
