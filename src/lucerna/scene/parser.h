// Lucerna scene reader: pbrt-v4 text-format parser entry points with options (host only).
// ParseSceneFile / ParseSceneString (description.h) use the default ParseOptions.
// Follows pbrt-v4's parser.cpp and BasicSceneBuilder (scene.cpp) for the graphics state.
#pragma once

#include <cstddef>
#include <string>

#include "lucerna/scene/description.h"

namespace lu {

struct ParseOptions {
    // Include/Import may open files. Off: they are SceneErrors (the fuzzer uses this).
    bool allowFileAccess = true;
    // Bounds on what hostile input can make the parser allocate.
    int maxIncludeDepth = 32;
    int maxAttributeDepth = 4096;
    size_t maxTotalValues = size_t(1) << 28;  // parameter values stored, copies included
};

SceneDescription ParseSceneFile(const std::string &filename, Diagnostics &diag, const ParseOptions &options);
SceneDescription ParseSceneString(const std::string &text, const std::string &filename, Diagnostics &diag,
                                  const ParseOptions &options);

// The directory part of a path ("" for a bare file name), and `path` resolved against `dir`
// (absolute paths are returned unchanged).
std::string DirectoryOf(const std::string &path);
std::string ResolvePath(const std::string &dir, const std::string &path);

}  // namespace lu
