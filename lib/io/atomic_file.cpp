#include "io/atomic_file.hpp"

#include <system_error>

#include "core/error.hpp"

namespace fem::io {

AtomicFile::AtomicFile(std::filesystem::path path) : path_(std::move(path)) {
    partial_ = path_;
    partial_ += ".partial";
    std::error_code ec;
    if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path(), ec);
    out_.open(partial_, std::ios::binary | std::ios::trunc);
    if (!out_) throw InputError("cannot write file '" + path_.string() + "'");
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        out_.close();
        std::error_code ec;
        std::filesystem::remove(partial_, ec);
    }
}

void AtomicFile::commit() {
    out_.flush();
    if (!out_) throw InputError("writing file '" + path_.string() + "' failed");
    out_.close();
    std::filesystem::rename(partial_, path_);
    committed_ = true;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
    AtomicFile file(path);
    file.stream() << text;
    file.commit();
}

}  // namespace fem::io
