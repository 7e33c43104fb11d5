#include "io/run_folder.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fem::io {
namespace fs = std::filesystem;

namespace {

// The pending list's first line: the staging folder whose files it lists.
const std::string pending_header = "# staging folder ";

[[noreturn]] void cannot_write(const fs::path& dir, const std::string& why) {
    throw InputError("cannot write to the output folder '" + dir.string() + "': " + why);
}

// The files under root, as paths relative to it (sorted: deterministic manifests).
std::vector<fs::path> files_under(const fs::path& root) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root))
        if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), root));
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<fs::path> read_manifest(const fs::path& file) {
    std::vector<fs::path> files;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] != '#') files.emplace_back(line);
    return files;
}

// A manifest entry must stay inside the folder ("../x" or "/x" in a corrupted manifest is ignored).
bool inside(const fs::path& relative) {
    if (relative.empty() || relative.is_absolute()) return false;
    for (const auto& part : relative)
        if (part == "..") return false;
    return true;
}

}  // namespace

RunFolder::RunFolder(fs::path dir, std::string program, Leftovers leftovers)
    : dir_(std::move(dir)), program_(std::move(program)) {
    std::error_code ec;
    if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec)) cannot_write(dir_, "it is a file, not a folder");
    if (!fs::exists(dir_, ec)) {
        fs::create_directories(dir_, ec);
        if (ec) cannot_write(dir_, ec.message());
        created_dir_ = true;
    }

    // The lock: flock on dir/.lock, released by the kernel when the process ends however it ends.
    // The file is removed on release; a run that opened it just before must then see that its lock
    // is on a removed file, so the path is checked to still be the locked file.
    lock_path_ = dir_ / ".lock";
    for (;;) {
        lock_fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (lock_fd_ < 0) {
            const std::string why = std::strerror(errno);
            release();
            cannot_write(dir_, why);
        }
        if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
            char pid[32] = {};
            const ssize_t n = ::pread(lock_fd_, pid, sizeof pid - 1, 0);
            ::close(lock_fd_);
            lock_fd_ = -1;
            const std::string holder = n > 0 ? std::string(pid, static_cast<std::size_t>(n)) : std::string("?");
            throw InputError("the output folder '" + dir_.string() + "' is in use by another run (" + holder +
                             "); wait for it to end or choose another folder");
        }
        struct stat held{}, now{};
        if (::fstat(lock_fd_, &held) == 0 && ::stat(lock_path_.c_str(), &now) == 0 && held.st_ino == now.st_ino &&
            held.st_dev == now.st_dev)
            break;
        ::close(lock_fd_);  // the holder removed the file between our open and flock: try again
        lock_fd_ = -1;
    }
    const std::string holder = program_ + " pid " + std::to_string(::getpid());
    if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, holder.data(), holder.size(), 0) < 0) {
        const std::string why = std::strerror(errno);
        release();
        cannot_write(dir_, why);
    }

    // Holding the lock, no live run uses the folder: staging folders and temporaries left by killed
    // runs can go (the newest staging folder stays when it is to be adopted: the killed run's).
    std::vector<fs::path> killed;
    for (const auto& entry : fs::directory_iterator(dir_, ec)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_directory() && name.rfind(".run-", 0) == 0) killed.push_back(entry.path());
    }
    if (leftovers == Leftovers::adopt && !killed.empty()) {
        const auto newest = std::max_element(killed.begin(), killed.end(), [](const fs::path& a, const fs::path& b) {
            std::error_code e;
            return fs::last_write_time(a, e) < fs::last_write_time(b, e);
        });
        staging_ = *newest;
        killed.erase(newest);
        adopted_ = true;
        // Killed while committing: the files it had already moved into place go back to its staging
        // folder, which is then whole again (the pending list names the staging folder it is of).
        std::error_code e;
        std::ifstream pending(dir_ / pending_name);
        std::string first;
        std::getline(pending, first);
        if (first == pending_header + staging_.filename().string())
            for (const auto& f : read_manifest(dir_ / pending_name))
                if (inside(f) && !fs::exists(staging_ / f, e) && fs::is_regular_file(dir_ / f, e)) {
                    fs::create_directories((staging_ / f).parent_path(), e);
                    fs::rename(dir_ / f, staging_ / f, e);
                }
    }
    for (const auto& k : killed) fs::remove_all(k, ec);
    for (const auto& entry : fs::recursive_directory_iterator(dir_, ec))
        if (entry.is_regular_file() && entry.path().extension() == ".partial") fs::remove(entry.path(), ec);
    if (adopted_) return;

    std::random_device rd;
    staging_ = dir_ / (".run-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000));
    fs::create_directory(staging_, ec);
    if (ec) {
        release();
        cannot_write(dir_, ec.message());
    }
}

RunFolder::~RunFolder() {
    if (!committed_ && !adopted_) {
        std::error_code ec;
        fs::remove_all(staging_, ec);
    }
    release();
}

void RunFolder::release() noexcept {
    std::error_code ec;
    if (lock_fd_ >= 0) {
        fs::remove(lock_path_, ec);  // while still holding it (see the constructor)
        ::close(lock_fd_);
        lock_fd_ = -1;
    }
    // A folder this run created and that holds nothing (a failed run) goes again.
    if (created_dir_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

void RunFolder::commit() {
    if (committed_) return;
    const std::vector<fs::path> mine = files_under(staging_);
    // The previous run's files, and those of a commit killed on the way (its pending list): files it
    // moved into place that this run does not write are stale too.
    std::vector<fs::path> previous = read_manifest(dir_ / manifest_name);
    for (const auto& f : read_manifest(dir_ / pending_name)) previous.push_back(f);
    std::ostringstream manifest;
    manifest << "# The files of the last completed run of " << program_
             << " in this folder; the next run into this folder replaces them.\n";
    for (const auto& f : mine) manifest << f.generic_string() << '\n';

    // The list first (a commit killed during the renames is then known to the next run), then the files
    // (each rename is atomic: a final name always holds a complete file), the manifest last.
    write_text_file(dir_ / pending_name, pending_header + staging_.filename().string() + "\n" + manifest.str());
    for (const auto& f : mine) {
        const fs::path to = dir_ / f;
        if (f.has_parent_path()) fs::create_directories(dir_ / f.parent_path());
        fs::rename(staging_ / f, to);
    }
    write_text_file(dir_ / manifest_name, manifest.str());
    // The previous run's files that this one did not write are stale.
    const std::set<fs::path> now(mine.begin(), mine.end());
    std::error_code ec;
    for (const auto& f : previous)
        if (inside(f) && !now.count(f) && f != manifest_name && f != pending_name) {
            fs::remove(dir_ / f, ec);
            for (fs::path p = f.parent_path(); !p.empty(); p = p.parent_path())  // empty subfolders of stale files
                if (fs::is_empty(dir_ / p, ec)) fs::remove(dir_ / p, ec);
        }
    fs::remove(dir_ / pending_name, ec);
    fs::remove_all(staging_, ec);
    committed_ = true;
    release();
}

}  // namespace fem::io
