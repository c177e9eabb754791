// The cloud a result refers to, however the user passed it: a surfgrow.Cloud (shared), the
// caller's own (N, 3) float32 array (read in place: no copy), or a converted copy of another array.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

#include "surfgrow/core/cloud_view.hpp"
#include "surfgrow/core/point_cloud.hpp"

namespace surfgrow::python {

class HeldCloud {
  public:
    /// `points` as the stages read it. An array that is float32, (N, 3), C-ordered and aligned
    /// is read in place and kept alive (no copy) unless `copy`; other arrays are converted once.
    static std::shared_ptr<const HeldCloud> hold(const pybind11::handle& points, const char* what,
                                                 bool copy = false);
    /// The same points with other sensor origins (occupancy's `origins`): one origin for every
    /// point, or one per scan of a cloud with scan_index. Offset already subtracted.
    static std::shared_ptr<const HeldCloud> with_origins(std::shared_ptr<const HeldCloud> held,
                                                         std::vector<Vec3d> origins);

    HeldCloud(const HeldCloud&) = delete;
    HeldCloud& operator=(const HeldCloud&) = delete;
    ~HeldCloud();

    /// What every stage reads: valid while this object lives.
    [[nodiscard]] const CloudView& view() const { return view_; }
    /// As a surfgrow.Cloud: the shared one, or (for arrays) a copy made on first use.
    [[nodiscard]] std::shared_ptr<PointCloud> cloud() const;

  private:
    HeldCloud() = default;

    CloudView view_;
    std::shared_ptr<const PointCloud> owned_;  // a Cloud, or a converted copy
    pybind11::object borrowed_;                // the caller's array (needs the GIL to let go)
    std::shared_ptr<const HeldCloud> base_;    // with_origins: the points' holder
    std::vector<Vec3d> origins_;               // with_origins: the view's scan origins
    mutable std::shared_ptr<PointCloud> as_cloud_;
};

using SharedCloud = std::shared_ptr<const HeldCloud>;

}  // namespace surfgrow::python
