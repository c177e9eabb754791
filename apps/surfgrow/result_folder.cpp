#include "result_folder.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::cli {

namespace fs = std::filesystem;

namespace {

// summary.orientation of surfaces.json, which io::read_result_json does not keep. The callback
// drops the surfaces array while parsing, so this second pass builds no large document.
OrientationSource read_orientation(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    const nlohmann::json::parser_callback_t skip_surfaces = [](int depth,
                                                               nlohmann::json::parse_event_t event,
                                                               nlohmann::json& parsed) {
        return !(depth == 1 && event == nlohmann::json::parse_event_t::key && parsed == "surfaces");
    };
    const nlohmann::json j = nlohmann::json::parse(in, skip_surfaces, /*allow_exceptions=*/false);
    std::string name;
    if (j.is_object() && j.contains("summary") && j["summary"].is_object())
        name = j["summary"].value("orientation", "");
    for (OrientationSource s : {OrientationSource::kScanOrigins, OrientationSource::kViewpoint,
                                OrientationSource::kFrameOrigin, OrientationSource::kUp})
        if (name == io::orientation_name(s)) return s;
    throw Error(ErrorCode::kMalformedInput,
                cat({file.string(), ": summary.orientation is missing or unknown ('", name, "')"}));
}

}  // namespace

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
    folder.result = io::read_result_json(file);
    folder.result.stats.orientation = read_orientation(file);
    return folder;
}

GrownCloud read_grown_cloud(const fs::path& cloud_file, const ResultFolder& folder) {
    GrownCloud g;
    g.cloud = io::read_cloud(cloud_file);
    // Bring the points into the result's frame if the file was read with another offset.
    const Vec3d shift = g.cloud.offset - folder.result.meta.offset;
    if (shift != Vec3d::Zero()) {
        const Vec3f s = shift.cast<float>();
        for (Vec3f& p : g.cloud.points) p += s;
        g.cloud.offset = folder.result.meta.offset;
    }
    const fs::path labels = folder.dir / "labels.txt";
    std::error_code ec;
    if (!fs::exists(labels, ec)) return g;
    g.labels = io::read_labels_txt(labels);
    if (g.labels.size() != g.cloud.size())
        throw Error(ErrorCode::kMalformedInput,
                    cat({labels.string(), " has ", std::to_string(g.labels.size()), " labels but ",
                         cloud_file.string(), " has ", std::to_string(g.cloud.size()),
                         " points: is this the cloud that was grown?"}));
    const auto surfaces = static_cast<std::int64_t>(folder.result.surfaces.size());
    for (std::size_t i = 0; i < g.labels.size(); ++i)
        if (g.labels[i] >= surfaces)
            throw Error(ErrorCode::kMalformedInput,
                        cat({labels.string(), ": line ", std::to_string(i + 1), " names surface ",
                             std::to_string(g.labels[i]), " but the result has ",
                             std::to_string(surfaces), " surfaces"}));
    return g;
}

}  // namespace surfgrow::cli
