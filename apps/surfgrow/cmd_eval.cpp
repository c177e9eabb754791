// `surfgrow eval OUT --truth SCAN [--require ...]`: accuracy of a result against ground truth.
#include <iostream>

#include "commands.hpp"
#include "eval_job.hpp"
#include "surfgrow/eval/report_text.hpp"

namespace surfgrow::cli {

void add_eval_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "eval", "Compare grown surfaces (a grow output folder) with a scan's ground truth");
    struct Args {
        std::string result;
        std::string truth;
        EvalSettings eval;
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    cmd->add_option("result", args->result, "Output folder of surfgrow grow")->required();
    cmd->add_option("--truth", args->truth,
                    "Output folder of surfgrow scan (cloud.ply, scene.json)")
        ->required();
    args->eval.add_to(*cmd);
    cmd->add_flag("-q,--quiet", args->quiet, "Only the eval line on stdout");
    cmd->callback([args] {
        // Options first: a bad --require fails before any file is read or written.
        const eval::EvalOptions options = args->eval.options();
        const std::vector<eval::Requirement> requirements = args->eval.requirements();
        const Truth truth = read_truth(args->truth);
        const eval::EvalReport report = evaluate_folder(args->result, truth, options);
        const auto checks = eval::check_requirements(requirements, report);
        write_eval_json(std::filesystem::path(args->result) / "eval.json", report, checks);
        if (!args->quiet) std::cout << eval::summary_text(report);
        std::cout << eval::eval_line(report) << "\n" << eval::requirements_text(checks);
        std::cout.flush();
        enforce(checks);
    });
}

}  // namespace surfgrow::cli
