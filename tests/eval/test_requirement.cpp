// --require bounds: syntax, percentages, unknown metrics, checking against a report.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/eval/metrics.hpp"
#include "surfgrow/eval/report_json.hpp"
#include "surfgrow/eval/report_text.hpp"
#include "surfgrow/eval/requirement.hpp"

namespace surfgrow::eval {
namespace {

EvalReport sample_report() {
    EvalReport r;
    r.all = {1000, 995};
    r.planar = {900, 899};
    r.normal_deg.median = 1.25;
    r.normal_deg.p95 = 4.5;
    r.residual_m.mean = 0.0015;
    r.purity = 0.99;
    r.normal_curved_deg.median = std::nan("");
    return r;
}

TEST(Requirement, ParsesTheDocumentedSyntax) {
    const auto reqs = parse_requirements(
        "registered>=0.99, normal_median <= 3,purity>98%,"
        "residual_mean_mm<2.5");
    ASSERT_EQ(reqs.size(), 4u);
    EXPECT_EQ(reqs[0].metric, "registered");
    EXPECT_EQ(reqs[0].op, Comparison::kAtLeast);
    EXPECT_DOUBLE_EQ(reqs[0].bound, 0.99);
    EXPECT_EQ(reqs[1].metric, "normal_median");
    EXPECT_EQ(reqs[1].op, Comparison::kAtMost);
    EXPECT_DOUBLE_EQ(reqs[1].bound, 3.0);
    EXPECT_EQ(reqs[2].op, Comparison::kAbove);
    EXPECT_DOUBLE_EQ(reqs[2].bound, 0.98);
    EXPECT_EQ(reqs[3].op, Comparison::kBelow);
    EXPECT_EQ(reqs[1].text, "normal_median <= 3");
}

TEST(Requirement, BadSyntaxIsAUsageErrorNamingThePart) {
    for (const std::string bad :
         {"registered", "registered>=", "registered>=abc", "speed>=1",
          "registered>=0.99,,purity>=0.9", "registered=>0.9", "registered>=1e999"}) {
        SCOPED_TRACE(bad);
        try {
            (void)parse_requirements(bad);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kUsage);
            EXPECT_NE(std::string(e.what()).find("--require"), std::string::npos) << e.what();
        }
    }
    try {
        (void)parse_requirements("speed>=1");
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("normal_median"), std::string::npos)
            << "lists the known metrics: " << e.what();
    }
}

TEST(Requirement, ChecksAgainstTheReport) {
    const EvalReport r = sample_report();
    const auto checks = check_requirements(
        parse_requirements("registered>=0.99,normal_median<=1,residual_mean_mm<=1.5,"
                           "normal_curved_median<=90"),
        r);
    ASSERT_EQ(checks.size(), 4u);
    EXPECT_TRUE(checks[0].met);
    EXPECT_DOUBLE_EQ(checks[0].value, 0.995);
    EXPECT_FALSE(checks[1].met);  // 1.25 > 1
    EXPECT_TRUE(checks[2].met);   // 1.5 mm exactly
    EXPECT_FALSE(checks[3].met);  // not available: a bound that cannot be checked fails
    const std::string text = requirements_text(checks);
    EXPECT_NE(text.find("normal_median<=1: 1.25 FAILED"), std::string::npos) << text;
    EXPECT_NE(text.find("registered>=0.99: 0.995 ok"), std::string::npos) << text;
}

TEST(Metrics, NamesAreUniqueAndCoverTheIssue) {
    const auto names = metric_names();
    for (std::size_t i = 0; i < names.size(); ++i)
        for (std::size_t j = i + 1; j < names.size(); ++j) EXPECT_NE(names[i], names[j]);
    for (const char* needed :
         {"registered", "registered_grown", "registered_planar", "registered_workspace",
          "registered_curved", "registered_unlabelled", "normal_median", "normal_p95",
          "facing_sensor", "purity", "residual_mean_mm", "surfaces_per_face", "data_reduction"})
        EXPECT_NE(std::find(names.begin(), names.end(), needed), names.end()) << needed;
}

TEST(ReportJson, MetricsByNameNullForUnknownAndDeterministic) {
    const EvalReport r = sample_report();
    const auto checks = check_requirements(parse_requirements("purity>=0.9"), r);
    const nlohmann::json j = to_json(r, checks);
    EXPECT_EQ(j.at("format"), "surfgrow-eval");
    EXPECT_DOUBLE_EQ(j.at("metrics").at("registered").get<double>(), 0.995);
    EXPECT_DOUBLE_EQ(j.at("metrics").at("residual_mean_mm").get<double>(), 1.5);
    EXPECT_TRUE(j.at("metrics").at("normal_curved_median").is_null());
    EXPECT_EQ(j.at("requirements").at(0).at("met"), true);
    EXPECT_EQ(to_json(r, checks).dump(), j.dump());
}

TEST(ReportText, OneLineWithTheHeadlineFigures) {
    const std::string line = eval_line(sample_report());
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_NE(line.find("99.5% registered"), std::string::npos) << line;
    EXPECT_NE(line.find("median 1.25 deg"), std::string::npos) << line;
}

}  // namespace
}  // namespace surfgrow::eval
