#pragma once
// A run's output folder as a unit: it holds the results of one run, never a mix of two.
//
//   io::RunFolder out(dir, "fem-modal");     // before solving: folder writable, lock taken, leftovers
//                                            // of killed runs removed; InputError otherwise
//   ... solve ...
//   write_results(out.staging(), ...);       // every file of the run goes to a private staging folder
//   out.commit();                            // the set replaces the previous run's, manifest.txt last
//
// Layout of dir while and after a run:
//   .lock               held (flock) for the run's lifetime: a second run into the same folder is
//                       refused ("in use by pid N") instead of mixing its files with the first's
//   .run-<pid>-<rand>/  the staging folder of a live run (removed by the next run if it was killed)
//   manifest.txt        the files of the last completed run, one per line
//   .manifest-pending   only while (or after a kill during) commit(): the files being moved into place
// commit() moves each staged file into place (rename: a file under its final name is always
// complete), writes the manifest, then removes files of the previous run's manifest that this run
// did not write (a rerun with 5 modes after 60 leaves no stale mode files). A run that ends without
// commit() (an error; SIGKILL) leaves the previous run's set as it was; a folder the run created
// and left empty is removed again. Files the manifest does not list (a user's own) are never
// touched.
//
// Resuming a killed run (fem-explicit --resume): RunFolder(dir, program, Leftovers::adopt) keeps the
// staging folder the killed run left (its restart dumps, its VTU files so far) and makes it this
// run's staging folder, under the same name (a restart dump records its paths, e.g. the VTU series',
// so the series continues); only its `*.partial` temporaries go. An adopted staging folder outlives
// a run that fails again, so that a later resume still finds it.
#include <filesystem>
#include <string>

namespace fem::io {

class RunFolder {
public:
    /// What becomes of the staging folder a killed run left in the folder.
    enum class Leftovers { remove, adopt };

    /// Prepares `dir` (created when missing) for a run of `program`; throws InputError when the
    /// folder cannot be written or another live run holds it. Leftovers::adopt: continue in the
    /// killed run's staging folder when there is one (adopted()), a fresh one otherwise.
    RunFolder(std::filesystem::path dir, std::string program, Leftovers leftovers = Leftovers::remove);
    ~RunFolder();
    RunFolder(const RunFolder&) = delete;
    RunFolder& operator=(const RunFolder&) = delete;

    /// The final folder.
    const std::filesystem::path& path() const { return dir_; }
    /// Where the run writes its files (same relative names as in the final folder).
    const std::filesystem::path& staging() const { return staging_; }
    /// Moves the staged files into place and writes the manifest (see above). Call once, at the end.
    void commit();
    bool committed() const { return committed_; }
    /// True when this run continues in the staging folder of a killed run (Leftovers::adopt).
    bool adopted() const { return adopted_; }

    /// The manifest's file name.
    static constexpr const char* manifest_name = "manifest.txt";
    /// The list of the files commit() is moving into place, written before the first and removed
    /// after the last: a run killed while committing leaves it, and the next run takes those files
    /// as stale too (or, adopting the killed run's staging folder, moves them back into it).
    static constexpr const char* pending_name = ".manifest-pending";

private:
    void release() noexcept;

    std::filesystem::path dir_, staging_, lock_path_;
    std::string program_;
    int lock_fd_ = -1;
    bool created_dir_ = false, committed_ = false, adopted_ = false;
};

}  // namespace fem::io
