// Lucerna test support: shared paths and temporary folders.
#include "support/test_support.h"

#include <filesystem>
#include <string>
#include <unistd.h>

namespace lu::test {

std::string SharedPath(const std::string &rel) { return std::string(LUCERNA_SHARED_DIR) + "/" + rel; }
std::string SourcePath(const std::string &rel) { return std::string(LUCERNA_SOURCE_DIR) + "/" + rel; }
std::string TempDir(const std::string &name) {
    // ctest runs each test in its own process, several at once: the pid keeps their folders apart.
    auto p = std::filesystem::temp_directory_path() / ("lucerna_test_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p.string();
}

}  // namespace lu::test
