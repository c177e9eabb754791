#include "surfgrow/scanner/raw_scan.hpp"

#include <cmath>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::scanner {

void RawScan::validate() const {
    spec.validate();
    check_rigid(pose);
    if (readings_mm.size() != spec.readings())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"raw scan holds ", std::to_string(readings_mm.size()),
                         " readings but its spec needs ", std::to_string(spec.readings())}));
    if (!truth_face_id.empty() && truth_face_id.size() != spec.rays())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"raw scan holds ", std::to_string(truth_face_id.size()),
                         " ground-truth ids but has ", std::to_string(spec.rays()), " rays"}));
    const auto per_position = [&](std::size_t size, const char* what) {
        if (size != 0 && size != static_cast<std::size_t>(spec.tilt.positions))
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"raw scan holds ", std::to_string(size), " ", what, " but has ",
                             std::to_string(spec.tilt.positions), " tilt positions"}));
    };
    per_position(tilt_read_deg.size(), "read-back tilt angles");
    per_position(sensor_time_ms.size(), "sensor time stamps");
    for (std::size_t i = 0; i < tilt_read_deg.size(); ++i)
        if (!std::isfinite(tilt_read_deg[i]) || std::abs(tilt_read_deg[i]) > 180.0)
            throw Error(
                ErrorCode::kInvalidParameter,
                cat({"read-back tilt angle ", std::to_string(tilt_read_deg[i]), " deg at position ",
                     std::to_string(i), " is not within [-180, 180]"}));
    if (planned_positions < 0 || planned_positions > 20000)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"planned tilt positions ", std::to_string(planned_positions),
                         " outside 0..20000"}));
    for (const std::string* text : {&note, &stop_reason})
        if (text->size() > kMaxRawScanNoteBytes)
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"raw-scan text of ", std::to_string(text->size()), " bytes (at most ",
                             std::to_string(kMaxRawScanNoteBytes), ")"}));
}

}  // namespace surfgrow::scanner
