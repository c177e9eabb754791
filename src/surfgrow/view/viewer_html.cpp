#include "surfgrow/view/viewer_html.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "surfgrow/core/error.hpp"
#include "surfgrow/view/assets.hpp"
#include "surfgrow/view/base64.hpp"

namespace surfgrow::view {

static_assert(std::endian::native == std::endian::little,
              "the page's typed arrays are little-endian, as the host's floats must be");

namespace {

using nlohmann::json;

using render::usable;

// The box around what the page frames first: the bulk of the disks, as the PNG frames them
// (render::bulk_disks); without disks the planes and path; the points only when there is
// nothing else (so stray far returns cannot shrink the view).
struct Box {
    Vec3d min = Vec3d::Constant(INFINITY);
    Vec3d max = Vec3d::Constant(-INFINITY);
    void add(const Vec3d& p, double r = 0) {
        if (!p.allFinite()) return;
        min = min.cwiseMin(p - Vec3d::Constant(r));
        max = max.cwiseMax(p + Vec3d::Constant(r));
    }
    [[nodiscard]] bool empty() const { return !(min.x() <= max.x()); }
};

Box framing_box(const ViewerScene& s, const std::vector<std::size_t>& disks) {
    Box box;
    const std::vector<std::uint8_t> bulk = render::bulk_disks(s.disks);
    for (std::size_t i : disks)
        if (bulk[i]) box.add(s.disks[i].center, s.disks[i].radius);
    if (box.empty() && s.planes)
        for (const PlanePolygon& p : *s.planes)
            for (const Vec3d& v : p.outline) box.add(v);
    if (box.empty() && s.path)
        for (const Vec3d& g : *s.path) box.add(g);
    if (box.empty())
        for (const render::ScenePoint& p : s.points) box.add(p.position.cast<double>());
    return box;
}

// How far from `center` anything of the page lies (the far clipping plane must reach it).
double reach_of(const ViewerScene& s, const std::vector<std::size_t>& disks, const Vec3d& center) {
    double r = 0;
    auto add = [&](const Vec3d& p, double extra) {
        if (p.allFinite()) r = std::max(r, (p - center).norm() + extra);
    };
    for (std::size_t i : disks) add(s.disks[i].center, s.disks[i].radius);
    if (s.planes)
        for (const PlanePolygon& p : *s.planes)
            for (const Vec3d& v : p.outline) add(v, 0);
    if (s.path)
        for (const Vec3d& g : *s.path) add(g, 0);
    for (const render::ScenePoint& p : s.points) add(p.position.cast<double>(), 0);
    return r;
}

// One binary array as an inert <script> block the page decodes with atob().
class Blocks {
  public:
    explicit Blocks(Vec3d center) : center_(std::move(center)) {}

    std::string add_positions(const std::string& id, const std::vector<Vec3d>& points) {
        std::vector<float> xyz;
        xyz.reserve(3 * points.size());
        for (const Vec3d& p : points)
            for (int a = 0; a < 3; ++a) xyz.push_back(static_cast<float>(p[a] - center_[a]));
        return add(id, xyz.data(), xyz.size() * sizeof(float));
    }
    std::string add_floats(const std::string& id, const std::vector<float>& v) {
        return add(id, v.data(), v.size() * sizeof(float));
    }
    std::string add_colors(const std::string& id, const std::vector<render::Rgb>& colors) {
        std::vector<std::uint8_t> rgb;
        rgb.reserve(3 * colors.size());
        for (const render::Rgb& c : colors) rgb.insert(rgb.end(), {c.r, c.g, c.b});
        return add(id, rgb.data(), rgb.size());
    }
    std::string add_bytes(const std::string& id, const std::vector<std::int8_t>& v) {
        return add(id, v.data(), v.size());
    }
    [[nodiscard]] const std::string& html() const { return html_; }
    [[nodiscard]] const Vec3d& center() const { return center_; }

  private:
    std::string add(const std::string& id, const void* data, std::size_t bytes) {
        html_ += "<script type=\"application/octet-stream\" id=\"";
        html_ += id;
        html_ += "\">";
        append_base64(html_, data, bytes);
        html_ += "</script>\n";
        return id;
    }
    Vec3d center_;
    std::string html_;
};

json rgb_json(render::Rgb c) {
    return json::array({c.r, c.g, c.b});
}

// The JSON in the page, with '<' escaped so no string in it can close its <script> block.
std::string script_safe(const json& j) {
    const std::string text = j.dump();
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (c == '<')
            out += "\\u003c";
        else
            out += c;
    }
    return out;
}

std::string html_escape(std::string_view text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

// The meta JSON and the data blocks of the page.
std::pair<json, std::string> page_data(const ViewerScene& s) {
    std::vector<std::size_t> disks;
    for (std::size_t i = 0; i < s.disks.size(); ++i)
        if (usable(s.disks[i])) disks.push_back(i);
    if (!s.disk_plane_colors.empty() && s.disk_plane_colors.size() != s.disks.size())
        throw Error(ErrorCode::kInvalidParameter, "viewer: disk_plane_colors must be one per disk");
    const Box box = framing_box(s, disks);
    const Vec3d center = box.empty() ? Vec3d::Zero() : Vec3d(0.5 * (box.min + box.max));
    const double radius = box.empty() ? 1.0 : std::max(0.5 * (box.max - box.min).norm(), 1e-9);
    Blocks blocks(center);
    json layers = json::object();

    if (!s.points.empty()) {
        std::vector<Vec3d> xyz;
        std::vector<render::Rgb> rgb;
        // Each point's surface normal (zero: none), so points go with their disk when the page
        // ghosts or hides the disks seen from behind.
        std::vector<std::int8_t> normals;
        xyz.reserve(s.points.size());
        rgb.reserve(s.points.size());
        normals.reserve(3 * s.points.size());
        for (const render::ScenePoint& p : s.points) {
            if (!is_finite(p.position)) continue;
            xyz.push_back(p.position.cast<double>());
            rgb.push_back(p.color);
            const auto k = static_cast<std::size_t>(p.disk);
            const bool known = p.disk >= 0 && k < s.disks.size() && usable(s.disks[k]);
            const Vec3d n = known ? Vec3d(s.disks[k].normal.normalized()) : Vec3d::Zero();
            for (int a = 0; a < 3; ++a)
                normals.push_back(static_cast<std::int8_t>(std::lround(127.0 * n[a])));
        }
        layers["cloud"] = {{"count", xyz.size()},
                           {"position", blocks.add_positions("sg-cloud-xyz", xyz)},
                           {"color", blocks.add_colors("sg-cloud-rgb", rgb)},
                           {"normal", blocks.add_bytes("sg-cloud-normal", normals)}};
    }
    if (!disks.empty()) {
        // Per disk: centre (3), unit normal (3), radius: 7 floats.
        std::vector<float> d;
        std::vector<render::Rgb> rgb, plane_rgb;
        d.reserve(7 * disks.size());
        for (std::size_t i : disks) {
            const render::Disk& k = s.disks[i];
            const Vec3d n = k.normal.normalized();
            for (int a = 0; a < 3; ++a) d.push_back(static_cast<float>(k.center[a] - center[a]));
            for (int a = 0; a < 3; ++a) d.push_back(static_cast<float>(n[a]));
            d.push_back(static_cast<float>(k.radius));
            rgb.push_back(k.color);
            if (!s.disk_plane_colors.empty()) plane_rgb.push_back(s.disk_plane_colors[i]);
        }
        std::vector<double> radii;
        for (std::size_t i : disks) radii.push_back(s.disks[i].radius);
        auto mid = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
        std::nth_element(radii.begin(), mid, radii.end());
        json l = {{"count", disks.size()},
                  {"median_radius", *mid},
                  {"disks", blocks.add_floats("sg-disks", d)},
                  {"color", blocks.add_colors("sg-disk-rgb", rgb)},
                  {"plane_color", nullptr}};
        if (!plane_rgb.empty())
            l["plane_color"] = blocks.add_colors("sg-disk-plane-rgb", plane_rgb);
        layers["surfaces"] = l;
    }
    layers["planes"] = nullptr;
    if (s.planes) {
        json polygons = json::array();
        std::vector<Vec3d> vertices;
        for (const PlanePolygon& p : *s.planes) {
            json holes = json::array();
            vertices.insert(vertices.end(), p.outline.begin(), p.outline.end());
            for (const auto& h : p.holes) {
                holes.push_back(h.size());
                vertices.insert(vertices.end(), h.begin(), h.end());
            }
            polygons.push_back({{"plane", p.plane},
                                {"color", rgb_json(p.color)},
                                {"outline", p.outline.size()},
                                {"holes", holes}});
        }
        layers["planes"] = {{"polygons", polygons},
                            {"vertices", blocks.add_positions("sg-plane-xyz", vertices)}};
    }
    layers["path"] = nullptr;
    if (s.path)
        layers["path"] = {{"count", s.path->size()},
                          {"goals", blocks.add_positions("sg-path-xyz", *s.path)}};

    const Vec3d origin = s.offset + center;
    json meta = {
        {"format", "surfgrow-view"},
        {"version", 1},
        {"title", s.title},
        {"units", s.units},
        {"legend", s.legend},
        {"notes", s.notes},
        {"origin", {origin.x(), origin.y(), origin.z()}},
        {"radius", radius},
        {"reach", std::max(radius, reach_of(s, disks, center))},
        {"back_faces", s.back_faces == render::BackFaces::kShow    ? "show"
                       : s.back_faces == render::BackFaces::kGhost ? "ghost"
                                                                   : "hide"},
        {"layers", layers},
    };
    return {meta, blocks.html()};
}

}  // namespace

void write_viewer_html(std::ostream& out, const ViewerScene& scene) {
    const auto [meta, data] = page_data(scene);
    const std::string meta_text = script_safe(meta);
    const std::string title = html_escape(scene.title.empty() ? "surfgrow view" : scene.title);
    // The template's markers, each replaced by its text (docs/viewer.md: page layout).
    const std::array<std::pair<std::string_view, std::string_view>, 7> parts{{
        {"@TITLE@", title},
        {"@CSS@", assets::page_css()},
        {"@META@", meta_text},
        {"@DATA@", data},
        {"@THREE@", assets::three_js()},
        {"@ORBIT@", assets::orbit_controls_js()},
        {"@VIEWER@", assets::page_js()},
    }};
    std::string_view rest = assets::page_template();
    while (!rest.empty()) {
        std::size_t at = rest.find('@');
        const std::pair<std::string_view, std::string_view>* hit = nullptr;
        while (at != std::string_view::npos) {
            for (const auto& p : parts)
                if (rest.substr(at, p.first.size()) == p.first) hit = &p;
            if (hit) break;
            at = rest.find('@', at + 1);
        }
        out.write(rest.data(), static_cast<std::streamsize>(std::min(at, rest.size())));
        if (!hit) break;
        out.write(hit->second.data(), static_cast<std::streamsize>(hit->second.size()));
        rest.remove_prefix(at + hit->first.size());
    }
    if (!out) throw Error(ErrorCode::kCannotWrite, "viewer: the page could not be written");
}

std::string viewer_html(const ViewerScene& scene) {
    std::ostringstream out;
    write_viewer_html(out, scene);
    return std::move(out).str();
}

}  // namespace surfgrow::view
