#include "result_folder.hpp"

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::cli {

namespace fs = std::filesystem;

io::StoredResult read_grown_result(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw Error(ErrorCode::kCannotOpen,
                    cat({dir.string(), " is not a result folder (run `surfgrow grow` first)"}));
    return io::read_result_json(dir / "surfaces.json");
}

GrownFolder read_grown_folder(const fs::path& dir, const fs::path& cloud_file) {
    GrownFolder f;
    f.result = read_grown_result(dir);
    f.cloud = io::read_cloud(cloud_file);
    f.labels = io::read_labels_txt(dir / "labels.txt");
    if (f.labels.size() != f.cloud.size())
        throw Error(
            ErrorCode::kMalformedInput,
            cat({(dir / "labels.txt").string(), " has ", std::to_string(f.labels.size()),
                 " labels but ", cloud_file.string(), " has ", std::to_string(f.cloud.size()),
                 " points: is this the cloud the result was grown from?"}));
    const std::size_t surfaces = f.result.surfaces.size();
    for (std::size_t i = 0; i < f.labels.size(); ++i)
        if (f.labels[i] >= 0 && static_cast<std::size_t>(f.labels[i]) >= surfaces)
            throw Error(ErrorCode::kMalformedInput,
                        cat({(dir / "labels.txt").string(), " line ", std::to_string(i + 1),
                             ": surface ", std::to_string(f.labels[i]), " but ",
                             (dir / "surfaces.json").string(), " has ", std::to_string(surfaces)}));
    // Same file, same offset; a cloud re-saved with another offset is moved into the result's.
    const Vec3d shift = f.cloud.offset - f.result.meta.offset;
    if (shift != Vec3d::Zero()) {
        for (Vec3f& p : f.cloud.points) p = (p.cast<double>() + shift).cast<float>();
        f.cloud.offset = f.result.meta.offset;
    }
    return f;
}

}  // namespace surfgrow::cli
