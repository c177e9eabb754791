#include "result_folder.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <utility>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::cli {

namespace fs = std::filesystem;

namespace {

// summary.orientation of surfaces.json, which io::read_result_json does not keep. A SAX pass that
// stops at the surfaces array: surfgrow writes the summary before it, so this reads only the
// head of the file (a 30 MB result costs microseconds, not a second parse).
class OrientationReader : public nlohmann::json_sax<nlohmann::json> {
  public:
    explicit OrientationReader(bool whole_file) : whole_file_(whole_file) {}
    std::string orientation;

    bool key(string_t& k) override {
        if (depth_ == 1) {
            in_summary_ = k == "summary";
            if (k == "surfaces" && !whole_file_) return false;  // stop: the summary came first
        }
        at_orientation_ = depth_ == 2 && in_summary_ && k == "orientation";
        return true;
    }
    bool string(string_t& v) override {
        if (at_orientation_) orientation = v;
        return done();
    }
    bool start_object(std::size_t) override { return ++depth_, done(); }
    bool end_object() override { return --depth_, done(); }
    bool start_array(std::size_t) override { return ++depth_, done(); }
    bool end_array() override { return --depth_, done(); }
    bool null() override { return done(); }
    bool boolean(bool) override { return done(); }
    bool number_integer(number_integer_t) override { return done(); }
    bool number_unsigned(number_unsigned_t) override { return done(); }
    bool number_float(number_float_t, const string_t&) override { return done(); }
    bool binary(binary_t&) override { return done(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

  private:
    bool done() {
        at_orientation_ = false;
        return true;
    }
    bool whole_file_;
    int depth_ = 0;
    bool in_summary_ = false;
    bool at_orientation_ = false;
};

OrientationSource read_orientation(const fs::path& file) {
    std::string name;
    for (const bool whole_file : {false, true}) {  // the whole file only if the summary came last
        std::ifstream in(file, std::ios::binary);
        OrientationReader reader(whole_file);
        nlohmann::json::sax_parse(in, &reader);
        name = reader.orientation;
        if (!name.empty()) break;
    }
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

io::StoredResult read_grown_result(const fs::path& dir) {
    return read_result_folder(dir).result;
}

GrownFolder read_grown_folder(const fs::path& dir, const fs::path& cloud_file) {
    ResultFolder folder = read_result_folder(dir);
    GrownCloud g = read_grown_cloud(cloud_file, folder);
    std::error_code ec;
    if (!fs::exists(dir / "labels.txt", ec))
        throw Error(ErrorCode::kCannotOpen,
                    cat({(dir / "labels.txt").string(),
                         " is missing (was the result grown with --no-labels?)"}));
    return GrownFolder{std::move(folder.result), std::move(g.cloud), std::move(g.labels)};
}

}  // namespace surfgrow::cli
