#include "surfgrow/io/result_folder.hpp"

#include <utility>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/grown_points.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::io {

namespace fs = std::filesystem;

ResultFolder read_result_folder(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw Error(
            ErrorCode::kCannotOpen,
            cat({dir.string(), ": no such folder (give the folder surfgrow grow -o wrote)"}));
    const fs::path file = dir / "surfaces.json";
    if (!fs::is_regular_file(file, ec))
        throw Error(ErrorCode::kCannotOpen,
                    cat({dir.string(), ": no surfaces.json here (is this a surfgrow result?)"}));
    ResultFolder folder;
    folder.dir = dir;
    folder.result = read_result_json(file);
    return folder;
}

void check_derived_file(const fs::path& file, const ResultMeta& meta,
                        std::optional<std::size_t> surfaces, const StoredResult& result,
                        std::string_view redo) {
    const fs::path surfaces_json = file.parent_path() / "surfaces.json";
    if (!result.meta.result_id.empty() && meta.result_id != result.meta.result_id)
        throw Error(ErrorCode::kMalformedInput,
                    cat({file.string(), " belongs to another result (result_id \"", meta.result_id,
                         "\", ", surfaces_json.string(), " has \"", result.meta.result_id,
                         "\"): left from an earlier run or copied from another folder; ", redo}));
    if (meta.units != result.meta.units)
        throw Error(ErrorCode::kMalformedInput,
                    cat({file.string(), ": lengths are in \"", meta.units, "\" but ",
                         surfaces_json.string(), "'s are in \"", result.meta.units, "\"; ", redo}));
    if (surfaces && *surfaces != result.surfaces.size())
        throw Error(ErrorCode::kMalformedInput,
                    cat({file.string(), " was computed from ", std::to_string(*surfaces),
                         " surfaces but ", surfaces_json.string(), " has ",
                         std::to_string(result.surfaces.size()), "; ", redo}));
}

GrownCloud read_grown_cloud(const fs::path& cloud_file, const ResultFolder& folder) {
    GrownCloud g;
    g.cloud = read_cloud(cloud_file, kPointsOnly);
    // Bring the points into the result's frame if the file was read with another offset.
    const Vec3d shift = g.cloud.offset - folder.result.meta.offset;
    if (shift != Vec3d::Zero()) {
        const Vec3f s = shift.cast<float>();
        for (Vec3f& p : g.cloud.points) p += s;
        g.cloud.offset = folder.result.meta.offset;
    }
    const fs::path labels = labels_file(folder.dir);
    std::error_code ec;
    if (!fs::exists(labels, ec)) return g;
    g.labels = read_labels(labels);
    if (g.labels.size() != g.cloud.size())
        throw Error(ErrorCode::kMalformedInput,
                    cat({labels.string(), " has ", std::to_string(g.labels.size()), " labels but ",
                         cloud_file.string(), " has ", std::to_string(g.cloud.size()),
                         " points: is this the cloud that was grown?"}));
    // Same size, other points: the points the grower would index give it away.
    const std::vector<std::uint8_t> grown = grown_point_mask(g.cloud, folder.result.config);
    std::uint64_t n_grown = 0;
    for (const std::uint8_t in : grown) n_grown += in;
    if (n_grown != folder.result.stats.valid_points)
        throw Error(ErrorCode::kMalformedInput,
                    cat({cloud_file.string(), " has ", std::to_string(n_grown),
                         " points to grow but ", (folder.dir / "surfaces.json").string(), " says ",
                         std::to_string(folder.result.stats.valid_points),
                         ": is this the cloud that was grown?"}));
    const auto surfaces = static_cast<std::int64_t>(folder.result.surfaces.size());
    for (std::size_t i = 0; i < g.labels.size(); ++i) {
        if (g.labels[i] >= surfaces)
            throw Error(ErrorCode::kMalformedInput,
                        cat({labels.string(), ": point ", std::to_string(i),
                             "'s label names surface ", std::to_string(g.labels[i]),
                             " but the result has ", std::to_string(surfaces), " surfaces"}));
        if (g.labels[i] >= 0 && !grown[i])
            throw Error(ErrorCode::kMalformedInput,
                        cat({labels.string(), ": point ", std::to_string(i),
                             " has a surface but was not grown (NaN or outside the workspace)"}));
    }
    return g;
}

StoredResult read_grown_result(const fs::path& dir) {
    return read_result_folder(dir).result;
}

GrownFolder read_grown_folder(const fs::path& dir, const fs::path& cloud_file) {
    ResultFolder folder = read_result_folder(dir);
    GrownCloud g = read_grown_cloud(cloud_file, folder);
    const fs::path labels = labels_file(dir);
    std::error_code ec;
    if (!fs::exists(labels, ec))
        throw Error(ErrorCode::kCannotOpen,
                    cat({labels.string(), " is missing (was the result grown with --no-labels?)"}));
    return GrownFolder{std::move(folder.result), std::move(g.cloud), std::move(g.labels)};
}

}  // namespace surfgrow::io
