#include "surfgrow/render/raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::render {

namespace {

constexpr std::uint32_t pack(Rgb c) {
    return (std::uint32_t(c.r) << 16) | (std::uint32_t(c.g) << 8) | std::uint32_t(c.b);
}

// First and last index whose sample centre (origin + k + 0.5) lies in [lo, hi], k in [0, n).
inline bool sample_span(double lo, double hi, int origin, int n, int& first, int& last) {
    const double f = std::ceil(lo - 0.5) - origin, l = std::floor(hi - 0.5) - origin;
    if (!(f <= l) || l < 0 || f >= n) return false;
    first = f < 0 ? 0 : static_cast<int>(f);
    last = l >= n - 1 ? n - 1 : static_cast<int>(l);
    return first <= last;
}

}  // namespace

double ScreenEllipse::half_width() const {
    return std::sqrt(a * a * ux * ux + b * b * uy * uy);
}
double ScreenEllipse::half_height() const {
    return std::sqrt(a * a * uy * uy + b * b * ux * ux);
}

Raster::Raster(int samples, int apron) : ss_(samples), apron_(apron) {
    if (samples < 1 || samples > 4 || apron < 0)
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"raster needs 1 to 4 samples per pixel and an apron >= 0, got ",
                         num(samples), " and ", num(apron)}));
}

void Raster::reset(int x0, int y0, int width, int height, Rgb background) {
    x0_ = x0, y0_ = y0, width_ = std::max(width, 0), height_ = std::max(height, 0);
    gx0_ = x0 * ss_ - apron_, gy0_ = y0 * ss_ - apron_;
    bw_ = width_ * ss_ + 2 * apron_, bh_ = height_ * ss_ + 2 * apron_;
    ghost_phase_ = ((gx0_ + gy0_) % 3 + 3) % 3;
    const std::size_t n = static_cast<std::size_t>(bw_) * static_cast<std::size_t>(bh_);
    color_.assign(n, pack(background));
    depth_.assign(n, std::numeric_limits<float>::infinity());
}

bool Raster::span_x(double lo, double hi, int& first, int& last) const {
    return sample_span(lo, hi, gx0_, bw_, first, last);
}
bool Raster::span_y(double lo, double hi, int& first, int& last) const {
    return sample_span(lo, hi, gy0_, bh_, first, last);
}

void Raster::fill_ellipse(const ScreenEllipse& e) {
    const double s = ss_;
    const double cx = e.cx * s, cy = e.cy * s, a = e.a * s, b = e.b * s;
    if (!(a > 0) || !(b > 0) || !std::isfinite(cx) || !std::isfinite(cy)) return;
    const double ux = e.ux, uy = e.uy;
    const double ia2 = 1 / (a * a), ib2 = 1 / (b * b);
    // alpha = (d . u) / a, beta = (d . v) / b with v = (-uy, ux); inside: alpha^2 + beta^2 <= 1.
    // Along a row that is a quadratic in dx: qa dx^2 + qb dx + qc <= 0.
    const double qa = ux * ux * ia2 + uy * uy * ib2;
    const double half_h = e.half_height() * s;
    int j0 = 0, j1 = 0;
    if (!span_y(cy - half_h, cy + half_h, j0, j1)) return;
    const std::uint32_t fill = pack(e.fill), rim = pack(e.rim);
    const double rim_start = e.rim_start;
    const double da = ux / a, db = -uy / b;
    for (int j = j0; j <= j1; ++j) {
        const double dy = gy0_ + j + 0.5 - cy;
        const double qb = 2 * dy * ux * uy * (ia2 - ib2);
        const double qc = dy * dy * (uy * uy * ia2 + ux * ux * ib2) - 1;
        const double disc = qb * qb - 4 * qa * qc;
        if (disc < 0) continue;
        const double root = std::sqrt(disc);
        int i0 = 0, i1 = 0;
        if (!span_x(cx + (-qb - root) / (2 * qa), cx + (-qb + root) / (2 * qa), i0, i1)) continue;
        const double dx = gx0_ + i0 + 0.5 - cx;
        double alpha = (dx * ux + dy * uy) / a;
        double beta = (dy * ux - dx * uy) / b;
        const std::size_t row = index(0, j);
        if (!ghost_) {
            for (int i = i0; i <= i1; ++i, alpha += da, beta += db)
                put(row + static_cast<std::size_t>(i),
                    static_cast<float>(e.depth + beta * e.depth_b),
                    alpha * alpha + beta * beta > rim_start ? rim : fill);
            continue;
        }
        // Ghosts: one sample in three, counted along the row instead of a modulo per sample.
        int phase = (i0 + j + ghost_phase_) % 3;
        for (int i = i0; i <= i1; ++i, alpha += da, beta += db) {
            const bool drawn = phase == 0;
            phase = phase == 2 ? 0 : phase + 1;
            if (drawn)
                put(row + static_cast<std::size_t>(i),
                    static_cast<float>(e.depth + beta * e.depth_b),
                    alpha * alpha + beta * beta > rim_start ? rim : fill);
        }
    }
}

void Raster::fill_dot(double x, double y, double depth, double radius, Rgb color) {
    const double s = ss_;
    const double cx = x * s, cy = y * s;
    // Any point lies within sqrt(1/2) of a sample centre: the dot never vanishes.
    const double r = std::max(radius * s, 0.7072);
    if (!std::isfinite(cx) || !std::isfinite(cy)) return;
    int j0 = 0, j1 = 0;
    if (!span_y(cy - r, cy + r, j0, j1)) return;
    const std::uint32_t c = pack(color);
    const auto d = static_cast<float>(depth);
    for (int j = j0; j <= j1; ++j) {
        const double dy = gy0_ + j + 0.5 - cy;
        const double half = std::sqrt(std::max(r * r - dy * dy, 0.0));
        int i0 = 0, i1 = 0;
        if (!span_x(cx - half, cx + half, i0, i1)) continue;
        const std::size_t row = index(0, j);
        for (int i = i0; i <= i1; ++i) plot(row + static_cast<std::size_t>(i), i, j, d, c);
    }
}

void Raster::draw_segment(double x0, double y0, double d0, double x1, double y1, double d1,
                          double half_width, Rgb color) {
    const double s = ss_;
    x0 *= s, y0 *= s, x1 *= s, y1 *= s;
    if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1))
        return;
    const double hw = std::max(half_width * s, 0.7072);
    const double dx = x1 - x0, dy = y1 - y0;
    const double len2 = dx * dx + dy * dy;
    int j0 = 0, j1 = 0;
    if (!span_y(std::min(y0, y1) - hw, std::max(y0, y1) + hw, j0, j1)) return;
    const std::uint32_t c = pack(color);
    for (int j = j0; j <= j1; ++j) {
        const double yc = gy0_ + j + 0.5;
        // The part of the centre line within hw of this row, widened by hw: every sample of
        // the row within hw of the segment lies in that span.
        double t_lo = 0, t_hi = 1;
        if (std::abs(dy) > 1e-12) {
            t_lo = (yc - hw - y0) / dy;
            t_hi = (yc + hw - y0) / dy;
            if (t_lo > t_hi) std::swap(t_lo, t_hi);
            t_lo = std::max(t_lo, 0.0);
            t_hi = std::min(t_hi, 1.0);
            if (t_lo > t_hi) continue;
        }
        const double xa = x0 + t_lo * dx, xb = x0 + t_hi * dx;
        int i0 = 0, i1 = 0;
        if (!span_x(std::min(xa, xb) - hw, std::max(xa, xb) + hw, i0, i1)) continue;
        const std::size_t row = index(0, j);
        for (int i = i0; i <= i1; ++i) {
            const double px = gx0_ + i + 0.5 - x0, py = yc - y0;
            const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
            const double ex = px - t * dx, ey = py - t * dy;
            if (ex * ex + ey * ey > hw * hw) continue;
            plot(row + static_cast<std::size_t>(i), i, j, static_cast<float>(d0 + t * (d1 - d0)),
                 c);
        }
    }
}

void Raster::outline(double step, Rgb color, double strength) {
    if (!(step > 0) || !(strength > 0) || bw_ == 0 || bh_ == 0) return;
    scratch_ = depth_;                      // read the depths before any change
    const int reach = std::max(1, apron_);  // about a pixel wide in all
    const auto fstep = static_cast<float>(step);
    const std::uint32_t ink = pack(color);
    const auto w = static_cast<std::uint32_t>(std::lround(std::clamp(strength, 0.0, 1.0) * 256));
    auto mix_ink = [&](std::size_t i) {
        const std::uint32_t c = color_[i];
        auto ch = [&](int shift) {
            const std::uint32_t a = (c >> shift) & 0xff, b = (ink >> shift) & 0xff;
            return ((a * (256 - w) + b * w) >> 8) << shift;
        };
        color_[i] = ch(16) | ch(8) | ch(0);
    };
    // Only the window's own samples change; the apron is there to be looked at.
    const int lo_x = apron_, hi_x = bw_ - apron_, lo_y = apron_, hi_y = bh_ - apron_;
    if (apron_ == 0) {
        // No apron: neighbours past the buffer's edge count as not farther.
        auto farther = [&](float d, int bx, int by) {
            if (bx < 0 || by < 0 || bx >= bw_ || by >= bh_) return false;
            return scratch_[index(bx, by)] - d > fstep;  // background (infinity) is farther
        };
        for (int by = lo_y; by < hi_y; ++by)
            for (int bx = lo_x; bx < hi_x; ++bx) {
                const float d = scratch_[index(bx, by)];
                if (std::isfinite(d) && (farther(d, bx + 1, by) || farther(d, bx - 1, by) ||
                                         farther(d, bx, by + 1) || farther(d, bx, by - 1)))
                    mix_ink(index(bx, by));
            }
        return;
    }
    // With an apron every neighbour within reach lies in the buffer: no bounds to check, and a
    // row's edge flags are computed without branches (vectorised). A background sample
    // (infinity) has no farther neighbour: inf - inf and finite - inf are not > step.
    const auto width = static_cast<std::size_t>(hi_x - lo_x);
    edge_.resize(width);
    const std::size_t stride = static_cast<std::size_t>(bw_);
    for (int by = lo_y; by < hi_y; ++by) {
        const float* mid = scratch_.data() + index(lo_x, by);
        std::fill(edge_.begin(), edge_.end(), std::uint8_t{0});
        for (int k = 1; k <= reach; ++k) {
            const auto ks = static_cast<std::size_t>(k);
            const float *up = mid - ks * stride, *down = mid + ks * stride;
            const float *left = mid - ks, *right = mid + ks;
            std::uint8_t* flag = edge_.data();
            for (std::size_t x = 0; x < width; ++x) {
                const float d = mid[x];
                flag[x] |=
                    static_cast<std::uint8_t>((right[x] - d > fstep) | (left[x] - d > fstep) |
                                              (down[x] - d > fstep) | (up[x] - d > fstep));
            }
        }
        const std::size_t row = index(lo_x, by);
        for (std::size_t x = 0; x < width; ++x)
            if (edge_[x]) mix_ink(row + x);
    }
}

namespace {

// 0x00RRGGBB spread into three 16-bit lanes: up to 257 samples add up without overflow.
inline std::uint64_t spread(std::uint32_t c) {
    return (std::uint64_t(c & 0xff0000) << 16) | (std::uint64_t(c & 0xff00) << 8) | (c & 0xff);
}

template <int SS>
void resolve_rows(const std::uint32_t* color, std::size_t stride, int width, int height,
                  std::uint8_t* dst, std::size_t dst_stride) {
    constexpr std::uint64_t n = SS * SS;
    for (int y = 0; y < height; ++y) {
        const std::uint32_t* rows = color + static_cast<std::size_t>(y) * SS * stride;
        std::uint8_t* out = dst + static_cast<std::size_t>(y) * dst_stride;
        for (int x = 0; x < width; ++x) {
            std::uint64_t sum = 0;
            for (int k = 0; k < SS; ++k)
                for (int m = 0; m < SS; ++m) sum += spread(rows[k * stride + x * SS + m]);
            out[3 * x] = static_cast<std::uint8_t>((((sum >> 32) & 0xffff) + n / 2) / n);
            out[3 * x + 1] = static_cast<std::uint8_t>((((sum >> 16) & 0xffff) + n / 2) / n);
            out[3 * x + 2] = static_cast<std::uint8_t>(((sum & 0xffff) + n / 2) / n);
        }
    }
}

}  // namespace

void Raster::resolve_into(Image& image) const {
    std::uint8_t* dst = image.bytes().data() + static_cast<std::size_t>(y0_) * image.row_stride() +
                        3 * static_cast<std::size_t>(x0_);
    const std::uint32_t* src = &color_[index(apron_, apron_)];
    const auto stride = static_cast<std::size_t>(bw_);
    switch (ss_) {
        case 1:
            resolve_rows<1>(src, stride, width_, height_, dst, image.row_stride());
            break;
        case 2:
            resolve_rows<2>(src, stride, width_, height_, dst, image.row_stride());
            break;
        case 3:
            resolve_rows<3>(src, stride, width_, height_, dst, image.row_stride());
            break;
        default:
            resolve_rows<4>(src, stride, width_, height_, dst, image.row_stride());
            break;
    }
}

}  // namespace surfgrow::render
