#include "surfgrow/scanner/raw_scan.hpp"

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
}

}  // namespace surfgrow::scanner
