// Lucerna CLI: the files a render writes, checked before the scene is read and again against the
// files it read: each must be a regular file or not exist, have a known image extension where an
// image is written, lie in a folder that exists or can be made, be writable by its mode bits, and
// be a different file (filesystem identity) from every other output and from every input.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace lu::app {

// A path and how the user named it ("-o", "--stats-json", "the scene file", ...).
struct NamedPath {
    std::string path;
    std::string role;
    bool image = false;   // an output image: .exr or .png
};

// "" when every output can be written; else one line naming the offending path and its option.
// Missing folders are allowed when the nearest existing one is a writable folder (they are made
// by CreateOutputFolders).
std::string CheckOutputs(const std::vector<NamedPath> &outputs);
// "" when no output is the same file as an input or as another output; else one line naming
// both. `allowed` lists (output role, input role) pairs that may name the same file.
std::string CheckDistinct(const std::vector<NamedPath> &outputs, const std::vector<NamedPath> &inputs,
                          const std::vector<std::pair<std::string, std::string>> &allowed = {});
// Makes the missing folders of the outputs; "" or the reason.
std::string CreateOutputFolders(const std::vector<NamedPath> &outputs);

// The same file: filesystem identity (device and inode) when both exist, else the same
// normalized absolute path (symbolic links of the existing part resolved).
bool SameFile(const std::string &a, const std::string &b);
// Whether the mode bits let this process's effective user write the file: the owner's bit when
// it owns it, else the group's when it is in the group, else the others'. Unlike access(W_OK) this
// also holds for root, so a file without write permission is read-only for everyone.
bool ModeAllowsWrite(unsigned mode, unsigned owner, unsigned group);

}  // namespace lu::app
