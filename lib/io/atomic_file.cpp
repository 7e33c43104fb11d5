#include "io/atomic_file.hpp"

#include <atomic>
#include <cctype>
#include <string>
#include <system_error>

#include <unistd.h>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::io {

std::filesystem::path partial_name(const std::filesystem::path& path) {
    // Unique per process and writer: two runs (or two writers of one run) never share a temporary.
    static std::atomic<unsigned> counter{0};
    std::filesystem::path p = path;
    p += fmt::format(".{}-{}.partial", ::getpid(), counter++);
    return p;
}

AtomicFile::AtomicFile(std::filesystem::path path) : path_(std::move(path)) {
    partial_ = partial_name(path_);
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

std::string safe_file_name(std::string_view name) {
    std::string s(name);
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    return s;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
    AtomicFile file(path);
    file.stream() << text;
    file.commit();
}

}  // namespace fem::io
