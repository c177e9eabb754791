#include "surfgrow/io/calibration_file.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <ostream>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/io/atomic_output.hpp"
#include "surfgrow/io/json_fields.hpp"
#include "surfgrow/io/scan_files_common.hpp"

namespace surfgrow::io {

namespace {

constexpr const char* kFormat = "surfgrow-calibration";

}  // namespace

std::string calibration_to_json(const scanner::CalibrationResult& r,
                                const std::vector<std::string>& scans) {
    nlohmann::ordered_json j;
    j["format"] = kFormat;
    j["version"] = 1;
    j["optical_offset_m"] = r.calibration.optical_offset_m;
    j["optical_offset_sigma_m"] = r.offset_sigma_m;
    j["tilt_zero_deg"] = r.calibration.tilt_zero_deg;
    j["tilt_zero_estimated"] = r.zero_estimated;
    j["tilt_zero_sigma_deg"] = r.zero_sigma_deg;
    j["surface"] = {{"normal", json_fields::vec_json(r.plane.normal)},
                    {"d_m", r.plane.d},
                    {"points", r.points},
                    {"rms_before_m", r.rms_before_m},
                    {"rms_after_m", r.rms_after_m},
                    {"bow_m", r.bow_m}};
    j["scans"] = scans;
    return j.dump(2) + "\n";
}

void write_calibration_file(const std::filesystem::path& path,
                            const scanner::CalibrationResult& result,
                            const std::vector<std::string>& scans) {
    const std::string text = calibration_to_json(result, scans);
    write_atomically(path, [&](std::ostream& out) { out << text; });
}

scanner::Calibration parse_calibration_json(std::string_view text, std::string_view name) {
    const std::filesystem::path file(name);
    const nlohmann::json j = json_fields::parse_text(text, file);
    if (!j.is_object() || !j.contains("format") || j["format"] != kFormat)
        json_fields::malformed(file, cat({"not a calibration file (format is not ", kFormat, ")"}));
    if (!j.contains("version") || j["version"] != 1)
        json_fields::malformed(file, "unsupported calibration version (this surfgrow reads 1)");
    const auto number = [&](const char* key, double limit) {
        if (!j.contains(key) || !j[key].is_number())
            json_fields::malformed(file, cat({key, " is missing or not a number"}));
        const double v = j[key].get<double>();
        if (!std::isfinite(v) || std::abs(v) > limit)
            json_fields::malformed(
                file, cat({key, " ", std::to_string(v), " is beyond ", std::to_string(limit)}));
        return v;
    };
    scanner::Calibration c;
    c.optical_offset_m = number("optical_offset_m", 0.999);
    c.tilt_zero_deg = number("tilt_zero_deg", 10.0);
    return c;
}

scanner::Calibration read_calibration_file(const std::filesystem::path& path) {
    const std::string text = detail::read_file_capped(path, 1 << 20, "a calibration file");
    return parse_calibration_json(text, path.string());
}

}  // namespace surfgrow::io
