// A result folder written by `surfgrow grow`, read back: the one way every command that works on
// an existing result (planes, coverage, occupancy, collide, eval, render, view) opens it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::io {

struct ResultFolder {
    std::filesystem::path dir;
    /// surfaces.json
    StoredResult result;
};

/// Reads dir/surfaces.json. Throws Error(kCannotOpen) if `dir` is not a folder or has no
/// surfaces.json, Error(kMalformedInput) if that file is not a surfgrow result.
[[nodiscard]] ResultFolder read_result_folder(const std::filesystem::path& dir);

/// Throws Error(kMalformedInput) naming `file` unless it belongs to `result`, the folder's
/// surfaces.json: the same result_id (when both have one: older folders have none), the same
/// units, and, when `surfaces` is given, computed from as many surfaces. `redo` says how to make
/// the file again (e.g. "run `surfgrow planes` again").
void check_derived_file(const std::filesystem::path& file, const ResultMeta& meta,
                        std::optional<std::size_t> surfaces, const StoredResult& result,
                        std::string_view redo);

/// The cloud a result was grown from, in the result's frame (positions relative to its offset),
/// with the surface of each point from its labels (labels.bin, or labels.txt in older folders;
/// empty when the folder has neither).
struct GrownCloud {
    PointCloud cloud;
    std::vector<std::int32_t> labels;
};

/// Reads `cloud_file` and the folder's labels (labels_file). Throws what read_cloud throws, and
/// Error(kMalformedInput) when the labels do not match the cloud (another count, or another count
/// of points the grower would index: not the cloud that was grown), name surfaces the result does
/// not have, or give a surface to a point that was not grown.
[[nodiscard]] GrownCloud read_grown_cloud(const std::filesystem::path& cloud_file,
                                          const ResultFolder& folder);

/// A result folder's surfaces with the cloud they were grown from and its labels (all required).
struct GrownFolder {
    StoredResult result;               ///< DIR/surfaces.json
    PointCloud cloud;                  ///< the cloud, in the result's frame (same offset)
    std::vector<std::int32_t> labels;  ///< DIR/labels.bin (or .txt), one per cloud point
};

/// read_result_folder(dir).result.
[[nodiscard]] StoredResult read_grown_result(const std::filesystem::path& dir);

/// read_result_folder and read_grown_cloud, and the labels must exist: throws
/// Error(kCannotOpen) when the result was grown with --no-labels.
[[nodiscard]] GrownFolder read_grown_folder(const std::filesystem::path& dir,
                                            const std::filesystem::path& cloud_file);

}  // namespace surfgrow::io
