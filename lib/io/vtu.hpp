#pragma once
// ParaView output: one VTU (VTK unstructured grid, XML) per state, and a PVD collection that lists
// them with their times, so that ParaView plays the series as an animation.
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace fem::io {

/// A field on the points or the cells of the mesh: values.size() == count * components, stored
/// point by point (or cell by cell, in block order).
struct Field {
    std::string name;
    int components = 1;
    std::vector<double> values;
};

struct VtuData {
    std::vector<Field> point_fields;  // e.g. "displacement" (3), "velocity" (3)
    std::vector<Field> cell_fields;   // e.g. "von_mises" (1), "density" (1)
};

/// Writes `mesh` (at coordinates `x`, or the mesh's own when empty) with its fields. Every block is
/// written; a cell field has one value per element over all blocks in block order. Adds a cell
/// field "part" (the block index). Atomic (see AtomicFile).
void write_vtu(const std::filesystem::path& path, const Mesh& mesh, const VtuData& data,
               std::span<const Vec3> x = {});

/// A time series of VTU files listed in one .pvd file.
class PvdSeries {
public:
    explicit PvdSeries(std::filesystem::path pvd_path);
    /// Writes <stem>_<index>.vtu beside the .pvd and lists it at `time`.
    void add(double time, const Mesh& mesh, const VtuData& data, std::span<const Vec3> x = {});
    /// Rewrites the .pvd (called by add as well, so the series is readable while a run goes on).
    void write() const;
    int size() const { return static_cast<int>(entries_.size()); }
    /// The listed files (time, file name beside the .pvd), e.g. for a restart to continue the series.
    const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
    /// Continues a series written before (a restarted run): the next file gets the next index.
    void resume(std::vector<std::pair<double, std::string>> entries) { entries_ = std::move(entries); }

private:
    std::filesystem::path path_;
    std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace fem::io
