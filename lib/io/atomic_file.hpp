#pragma once
// Writes a file so that it never exists half-written under its final name: the content goes to a
// temporary sibling `<name>.<pid>-<n>.partial` (unique per process and writer), and commit() renames
// it into place. A writer destroyed without commit() (an exception on the way) removes the
// temporary; one killed leaves it, and io::RunFolder removes such leftovers.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace fem::io {

class AtomicFile {
public:
    /// Opens the temporary `<path>.<pid>-<n>.partial` for writing, creating the parent folders; throws InputError naming
    /// the path when that fails.
    explicit AtomicFile(std::filesystem::path path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return out_; }
    /// Flushes, checks the stream and renames the temporary to the final path.
    void commit();
    /// The temporary path, for writers (such as HDF5) that open the file themselves.
    const std::filesystem::path& partial_path() const { return partial_; }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_, partial_;
    std::ofstream out_;
    bool committed_ = false;
};

/// The temporary name AtomicFile and H5Writer write `path` under: `<path>.<pid>-<n>.partial`.
std::filesystem::path partial_name(const std::filesystem::path& path);

/// Writes `text` to `path` atomically.
void write_text_file(const std::filesystem::path& path, const std::string& text);

/// `name` as a part of a file name (and a gnuplot column name): letters, digits, '-', '_' and '.'
/// kept, every other character '_'.
std::string safe_file_name(std::string_view name);

}  // namespace fem::io
