#include "io/hdf5.hpp"

#include <H5Cpp.h>

#include <mutex>
#include <optional>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fem::io {

namespace {
// Debian's HDF5 is built without thread safety: one HDF5 call at a time in the process (studies run
// independent cases on several threads, check/cases.hpp). Recursive: a writer may read.
std::recursive_mutex& hdf5_mutex() {
    static std::recursive_mutex m;
    return m;
}
}  // namespace

struct H5Writer::Impl {
    std::unique_lock<std::recursive_mutex> lock{hdf5_mutex()};  // first: released after the file closes
    std::filesystem::path path, partial;
    std::optional<H5::H5File> file;  // emplaced by the constructor (H5File assigns only by a deprecated implicit copy)
    bool committed = false;

    // Dataset creation without modification times (see the constructor).
    static H5::DSetCreatPropList untimed() {
        H5::DSetCreatPropList p;
        H5Pset_obj_track_times(p.getId(), false);
        return p;
    }

    // Creates the groups along "a/b/c" (not c itself).
    void make_parents(const std::string& dataset) {
        std::size_t pos = 0;
        while ((pos = dataset.find('/', pos + 1)) != std::string::npos) {
            const std::string group = dataset.substr(0, pos);
            if (group.empty()) continue;
            if (!file->nameExists(group)) {
                H5::LinkCreatPropList lcpl;
                hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
                H5Pset_obj_track_times(gcpl, false);
                const hid_t g = H5Gcreate2(file->getId(), group.c_str(), lcpl.getId(), gcpl, H5P_DEFAULT);
                H5Pclose(gcpl);
                if (g < 0) throw H5::GroupIException("H5Writer", "cannot create group " + group);
                H5Gclose(g);
            }
        }
    }
    // Calls f(object) with the file, group or dataset called `name` ("/" for the file).
    template <class F>
    void with_object(const std::string& name, F&& f) {
        if (name == "/" || name.empty()) {
            f(static_cast<H5::H5Object&>(*file));
        } else if (file->childObjType(name) == H5O_TYPE_GROUP) {
            H5::Group g = file->openGroup(name);
            f(static_cast<H5::H5Object&>(g));
        } else {
            H5::DataSet d = file->openDataSet(name);
            f(static_cast<H5::H5Object&>(d));
        }
    }
};

H5Writer::H5Writer(std::filesystem::path path) : impl_(std::make_unique<Impl>()) {
    impl_->path = std::move(path);
    impl_->partial = partial_name(impl_->path);
    if (impl_->path.has_parent_path()) std::filesystem::create_directories(impl_->path.parent_path());
    try {
        H5::Exception::dontPrint();
        // No object modification times: identical runs give byte-identical files (the root group
        // takes its setting from the file creation list, groups and datasets from theirs).
        H5::FileCreatPropList fcpl;
        H5Pset_obj_track_times(fcpl.getId(), false);
        impl_->file.emplace(impl_->partial.string(), H5F_ACC_TRUNC, fcpl);
    } catch (const H5::Exception& e) {
        throw InputError("cannot create HDF5 file '" + impl_->path.string() + "': " + e.getDetailMsg());
    }
}

H5Writer::~H5Writer() {
    if (!impl_->committed) {
        try {
            impl_->file->close();
        } catch (...) {
        }
        std::error_code ec;
        std::filesystem::remove(impl_->partial, ec);
    }
}

void H5Writer::write(const std::string& dataset, const std::vector<double>& values) {
    impl_->make_parents(dataset);
    hsize_t dims[1] = {values.size()};
    H5::DataSpace space(1, dims);
    auto ds = impl_->file->createDataSet(dataset, H5::PredType::NATIVE_DOUBLE, space, Impl::untimed());
    if (!values.empty()) ds.write(values.data(), H5::PredType::NATIVE_DOUBLE);
}

void H5Writer::write(const std::string& dataset, const Eigen::MatrixXd& values) {
    impl_->make_parents(dataset);
    hsize_t dims[2] = {static_cast<hsize_t>(values.rows()), static_cast<hsize_t>(values.cols())};
    H5::DataSpace space(2, dims);
    auto ds = impl_->file->createDataSet(dataset, H5::PredType::NATIVE_DOUBLE, space, Impl::untimed());
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major = values;
    if (values.size()) ds.write(row_major.data(), H5::PredType::NATIVE_DOUBLE);
}

void H5Writer::write_ints(const std::string& dataset, const std::vector<long long>& values) {
    impl_->make_parents(dataset);
    hsize_t dims[1] = {values.size()};
    H5::DataSpace space(1, dims);
    auto ds = impl_->file->createDataSet(dataset, H5::PredType::NATIVE_LLONG, space, Impl::untimed());
    if (!values.empty()) ds.write(values.data(), H5::PredType::NATIVE_LLONG);
}

void H5Writer::attribute(const std::string& object, const std::string& name, const std::string& value) {
    impl_->with_object(object, [&](H5::H5Object& obj) {
        H5::StrType type(H5::PredType::C_S1, value.size() ? value.size() : 1);
        auto attr = obj.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
        attr.write(type, value.c_str());
    });
}

void H5Writer::attribute(const std::string& object, const std::string& name, double value) {
    impl_->with_object(object, [&](H5::H5Object& obj) {
        auto attr = obj.createAttribute(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(H5S_SCALAR));
        attr.write(H5::PredType::NATIVE_DOUBLE, &value);
    });
}

void H5Writer::commit() {
    impl_->file->close();
    std::filesystem::rename(impl_->partial, impl_->path);
    impl_->committed = true;
}

namespace {
Eigen::MatrixXd read_matrix_from(H5::H5File& file, const std::string& dataset) {
    auto ds = file.openDataSet(dataset);
    auto space = ds.getSpace();
    hsize_t dims[2] = {1, 1};
    const int rank = space.getSimpleExtentDims(dims);
    const Eigen::Index rows = dims[0], cols = rank == 2 ? dims[1] : 1;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(rows, cols);
    if (m.size()) ds.read(m.data(), H5::PredType::NATIVE_DOUBLE);
    return m;
}
}  // namespace

Eigen::MatrixXd read_h5_matrix(const std::filesystem::path& path, const std::string& dataset) {
    const std::lock_guard<std::recursive_mutex> lock(hdf5_mutex());
    try {
        H5::Exception::dontPrint();
        H5::H5File file(path.string(), H5F_ACC_RDONLY);
        return read_matrix_from(file, dataset);
    } catch (const H5::Exception& e) {
        throw InputError("cannot read dataset '" + dataset + "' of '" + path.string() + "': " + e.getDetailMsg());
    }
}

struct H5Reader::Impl {
    H5::H5File file;
    template <class F>
    auto with_object(const std::string& name, F&& f) const {
        if (name == "/" || name.empty()) return f(static_cast<const H5::H5Object&>(file));
        if (file.childObjType(name) == H5O_TYPE_GROUP) {
            H5::Group g = file.openGroup(name);
            return f(static_cast<const H5::H5Object&>(g));
        }
        H5::DataSet d = file.openDataSet(name);
        return f(static_cast<const H5::H5Object&>(d));
    }
};

H5Reader::H5Reader(std::filesystem::path path) : path_(std::move(path)), impl_(std::make_unique<Impl>()) {
    if (!std::filesystem::exists(path_)) throw InputError("HDF5 file '" + path_.string() + "' does not exist");
    try {
        H5::Exception::dontPrint();
        impl_->file.openFile(path_.string(), H5F_ACC_RDONLY);
    } catch (const H5::Exception& e) {
        throw InputError("cannot open HDF5 file '" + path_.string() + "': " + e.getDetailMsg());
    }
}

H5Reader::~H5Reader() = default;

bool H5Reader::has(const std::string& name) const {
    try {
        // Every group on the way must exist for nameExists (HDF5 1.10+ checks only the last link).
        std::size_t pos = 0;
        while ((pos = name.find('/', pos + 1)) != std::string::npos)
            if (!impl_->file.nameExists(name.substr(0, pos))) return false;
        return impl_->file.nameExists(name);
    } catch (const H5::Exception&) {
        return false;
    }
}

Eigen::MatrixXd H5Reader::read_matrix(const std::string& dataset) const {
    try {
        return read_matrix_from(impl_->file, dataset);
    } catch (const H5::Exception& e) {
        throw InputError("cannot read dataset '" + dataset + "' of '" + path_.string() + "': " + e.getDetailMsg());
    }
}

std::vector<double> H5Reader::read(const std::string& dataset) const {
    const Eigen::MatrixXd m = read_matrix(dataset);
    return std::vector<double>(m.data(), m.data() + m.size());
}

std::vector<long long> H5Reader::read_ints(const std::string& dataset) const {
    try {
        auto ds = impl_->file.openDataSet(dataset);
        hsize_t dims[1] = {0};
        ds.getSpace().getSimpleExtentDims(dims);
        std::vector<long long> v(dims[0]);
        if (!v.empty()) ds.read(v.data(), H5::PredType::NATIVE_LLONG);
        return v;
    } catch (const H5::Exception& e) {
        throw InputError("cannot read dataset '" + dataset + "' of '" + path_.string() + "': " + e.getDetailMsg());
    }
}

double H5Reader::attribute_number(const std::string& object, const std::string& name) const {
    try {
        return impl_->with_object(object, [&](const H5::H5Object& obj) {
            double v = 0.0;
            obj.openAttribute(name).read(H5::PredType::NATIVE_DOUBLE, &v);
            return v;
        });
    } catch (const H5::Exception& e) {
        throw InputError("cannot read attribute '" + name + "' of '" + object + "' in '" + path_.string() +
                         "': " + e.getDetailMsg());
    }
}

std::string H5Reader::attribute_string(const std::string& object, const std::string& name) const {
    try {
        return impl_->with_object(object, [&](const H5::H5Object& obj) {
            H5::Attribute a = obj.openAttribute(name);
            std::string v;
            a.read(a.getStrType(), v);
            return v;
        });
    } catch (const H5::Exception& e) {
        throw InputError("cannot read attribute '" + name + "' of '" + object + "' in '" + path_.string() +
                         "': " + e.getDetailMsg());
    }
}

}  // namespace fem::io
