// `lucerna diff IMAGE REFERENCE`: error metrics between two images (logic in image/diff.cpp).
#include <iostream>
#include <memory>

#include "apps/commands.h"
#include "lucerna/image/diff.h"

namespace lu::app {

void RegisterDiff(CLI::App &app, CommandTable &table) {
    auto options = std::make_shared<DiffOptions>();
    CLI::App *sub = app.add_subcommand("diff", "Compare an image with a reference: error metrics");
    sub->footer(DiffMetricsHelp());
    sub->add_option("image", options->image, "Image to measure (.exr or .png)")->required();
    sub->add_option("reference", options->reference, "Reference image (.exr or .png)")->required();
    sub->add_option("--metric", options->metric, "mse, rmse, relmse, mape or all")
        ->transform(CLI::IsMember({"mse", "rmse", "relmse", "mape", "all"}, CLI::ignore_case))
        ->default_str("all");
    sub->add_option("--crop", options->crop, "Only pixels in [X0,X1) x [Y0,Y1): X0,Y0,X1,Y1");
    sub->add_option("--error-image", options->errorImage,
                    "Write the per-pixel error (the chosen metric, relmse for all) to OUT.exr or OUT.png");
    sub->add_option("--block", options->blockSize, "Compare BxB block means instead of pixels (noisy references)");
    sub->add_flag("--ztest", options->zTest,
                  "Also a block z-test (noise from the spread of v - r in each block, Sidak-corrected)");
    sub->add_option("--alpha", options->alpha, "Family-wise level of --ztest")->default_str("1e-4");
    table.Add(sub, [options] { return RunDiff(*options, std::cout, std::cerr); });
}

}  // namespace lu::app
