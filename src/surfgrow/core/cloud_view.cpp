#include "surfgrow/core/cloud_view.hpp"

namespace surfgrow {

CloudView::CloudView(const PointCloud& c)
    : points(c.points),
      offset(c.offset),
      viewpoint(c.viewpoint),
      scan_index(c.scan_index),
      scan_origins(c.scan_origins),
      labels(c.labels),
      normals(c.normals) {}

}  // namespace surfgrow
