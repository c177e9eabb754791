// Reading back what `surfgrow grow` wrote, for the commands that work on an existing result.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/io/results_io.hpp"

namespace surfgrow::cli {

/// A result folder's surfaces with the cloud they were grown from and its labels.
struct GrownFolder {
    io::StoredResult result;           ///< DIR/surfaces.json
    PointCloud cloud;                  ///< the cloud, in the result's frame (same offset)
    std::vector<std::int32_t> labels;  ///< DIR/labels.txt, one per cloud point
};

/// Reads DIR/surfaces.json. Throws Error(kCannotOpen) when DIR or the file is missing.
[[nodiscard]] io::StoredResult read_grown_result(const std::filesystem::path& dir);

/// Reads DIR/surfaces.json, DIR/labels.txt and `cloud_file`, and checks that they belong
/// together: one label per point, every label a surface. Throws Error(kMalformedInput) naming
/// the files when they do not.
[[nodiscard]] GrownFolder read_grown_folder(const std::filesystem::path& dir,
                                            const std::filesystem::path& cloud_file);

}  // namespace surfgrow::cli
