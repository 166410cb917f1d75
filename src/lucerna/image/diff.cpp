// Lucerna `diff` command logic: read two images, print metrics, optionally write an error image.
#include "lucerna/image/diff.h"

#include <fmt/format.h>

#include <optional>
#include <vector>

#include "lucerna/image/image.h"
#include "lucerna/image/metrics.h"

namespace lu {

const char *DiffMetricsHelp() {
    return "Metrics over the N = pixels x colour channels values v (image), r (reference) in the crop:\n"
           "  mse    = (1/N) sum (v - r)^2\n"
           "  rmse   = sqrt(mse)\n"
           "  relmse = (1/N) sum (v - r)^2 / (r^2 + 0.01)\n"
           "  mape   = (1/N) sum |v - r| / (|r| + 0.01)\n"
           "Colour channels: R,G,B (alpha ignored) or Y. With --block B, v and r are BxB block means.\n"
           "Output: one line \"metric value\" per metric. Exit status 2 on unreadable or mismatched images.";
}

int RunDiff(const DiffOptions &o, std::ostream &out, std::ostream &err) {
    std::vector<Metric> metrics;
    if (o.metric == "all")
        metrics = {Metric::MSE, Metric::RMSE, Metric::RelMSE, Metric::MAPE};
    else if (auto m = ParseMetric(o.metric))
        metrics = {*m};
    else {
        err << "lucerna diff: unknown metric '" << o.metric << "' (use mse, rmse, relmse, mape or all)\n";
        return 2;
    }
    if (o.blockSize < 0) {
        err << "lucerna diff: --block must be positive\n";
        return 2;
    }
    try {
        std::optional<Crop> crop;
        if (!o.crop.empty()) crop = ParseCrop(o.crop);
        Image image = ReadImage(o.image), reference = ReadImage(o.reference);
        ComparedChannels(image, reference);
        ResolveCrop(crop, image.width, image.height);

        ErrorStats stats = o.blockSize > 0 ? CompareBlockMeans(image, reference, o.blockSize, crop)
                                           : ComputeErrors(image, reference, crop);
        if (stats.nonFinite > 0)
            err << fmt::format("lucerna diff: warning: {} non-finite values (NaN or Inf)\n", stats.nonFinite);
        for (Metric m : metrics) out << fmt::format("{} {:.9g}\n", MetricName(m), stats.Get(m));

        if (o.zTest) {
            ZTestOptions zo;
            zo.blockSize = o.blockSize > 0 ? o.blockSize : 8;
            zo.alpha = o.alpha;
            zo.crop = crop;
            ZTestResult z = ZTestBlocks(image, reference, zo);
            out << fmt::format("zmax {:.6g}\nzbound {:.6g}\nztest {}\n", z.maxAbsZ, z.threshold,
                               z.Passed() ? "pass" : "fail");
            err << z.Summary() << "\n";
        }
        if (!o.errorImage.empty()) {
            Metric em = metrics.size() == 1 ? metrics[0] : Metric::RelMSE;
            ImageMetadata meta{{"lucerna.metric", MetricName(em)},
                               {"lucerna.image", o.image},
                               {"lucerna.reference", o.reference}};
            if (crop) meta["lucerna.crop"] = o.crop;
            WriteImage(o.errorImage, ErrorImage(image, reference, em, crop), meta);
        }
    } catch (const ImageError &e) {
        err << "lucerna diff: error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}

}  // namespace lu
