// Lucerna test support: paths to shared data; the chi-square harness (support/chi2.h).
#pragma once

#include <string>
#include <vector>

#include "support/chi2.h"

namespace lu::test {

// Path of a file under ../shared (scenes, refs).
std::string SharedPath(const std::string &rel);
// Path of a file in the source tree.
std::string SourcePath(const std::string &rel);
// A fresh temporary directory for one test.
std::string TempDir(const std::string &name);

}  // namespace lu::test
