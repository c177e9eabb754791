#include "surfgrow/eval/requirement.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/eval/metrics.hpp"

namespace surfgrow::eval {

namespace {

std::string known_names() {
    std::string out;
    for (const std::string_view n : metric_names()) {
        if (!out.empty()) out += ", ";
        out += n;
    }
    return out;
}

[[noreturn]] void bad(std::string_view part, std::string_view why) {
    throw Error(ErrorCode::kUsage, cat({"--require: '", part, "' ", why}));
}

Requirement parse_one(std::string_view part) {
    const std::string_view text = trim(part);
    const std::size_t at = text.find_first_of("<>");
    if (text.empty()) bad(part, "is empty (expected e.g. registered>=0.99)");
    if (at == std::string_view::npos)
        bad(text, "has no comparison (expected name>=value or name<=value)");
    Requirement r;
    r.text = std::string(text);
    r.metric = std::string(trim(text.substr(0, at)));
    std::string_view rest = text.substr(at);
    const bool equal = rest.size() > 1 && rest[1] == '=';
    if (rest[0] == '>') r.op = equal ? Comparison::kAtLeast : Comparison::kAbove;
    if (rest[0] == '<') r.op = equal ? Comparison::kAtMost : Comparison::kBelow;
    rest = trim(rest.substr(equal ? 2 : 1));
    const auto names = metric_names();
    if (std::find(names.begin(), names.end(), r.metric) == names.end())
        throw Error(ErrorCode::kUsage, cat({"--require: unknown metric '", r.metric,
                                            "' (known: ", known_names(), ")"}));
    const bool percent = !rest.empty() && rest.back() == '%';
    if (percent) rest = trim(rest.substr(0, rest.size() - 1));
    const auto [ptr, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), r.bound);
    if (rest.empty() || ec != std::errc() || ptr != rest.data() + rest.size() ||
        !std::isfinite(r.bound))
        bad(text, "does not end in a number");
    if (percent) r.bound /= 100.0;
    return r;
}

}  // namespace

std::vector<Requirement> parse_requirements(std::string_view text) {
    std::vector<Requirement> out;
    while (true) {
        const std::size_t comma = text.find(',');
        out.push_back(parse_one(text.substr(0, comma)));
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return out;
}

std::vector<RequirementCheck> check_requirements(const std::vector<Requirement>& requirements,
                                                 const EvalReport& report) {
    const std::vector<Metric> all = metrics(report);
    std::vector<RequirementCheck> out;
    for (const Requirement& req : requirements) {
        RequirementCheck c;
        c.requirement = req;
        c.value = std::numeric_limits<double>::quiet_NaN();
        for (const Metric& m : all) {
            if (m.name == req.metric) c.value = m.value;
        }
        switch (req.op) {
            case Comparison::kAtLeast:
                c.met = c.value >= req.bound;
                break;
            case Comparison::kAtMost:
                c.met = c.value <= req.bound;
                break;
            case Comparison::kAbove:
                c.met = c.value > req.bound;
                break;
            case Comparison::kBelow:
                c.met = c.value < req.bound;
                break;
        }
        out.push_back(c);
    }
    return out;
}

std::string_view to_string(Comparison op) {
    switch (op) {
        case Comparison::kAtLeast:
            return ">=";
        case Comparison::kAtMost:
            return "<=";
        case Comparison::kAbove:
            return ">";
        case Comparison::kBelow:
            return "<";
    }
    return "?";
}

}  // namespace surfgrow::eval
