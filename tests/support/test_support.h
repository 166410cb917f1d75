// Lucerna test support: paths to shared data and a chi-square goodness-of-fit helper.
#pragma once

#include <string>
#include <vector>

namespace lu::test {

// Path of a file under ../shared (scenes, refs).
std::string SharedPath(const std::string &rel);
// Path of a file in the source tree.
std::string SourcePath(const std::string &rel);
// A fresh temporary directory for one test.
std::string TempDir(const std::string &name);

// Pearson chi-square test of observed counts against expected counts (cells with expected < 5
// are pooled, as Mitsuba's chi2 harness does). Returns the p-value; *message gets a summary.
double ChiSquarePValue(const std::vector<double> &observed, const std::vector<double> &expected,
                       std::string *message = nullptr);

}  // namespace lu::test
