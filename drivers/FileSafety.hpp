// Which files a command reads and writes, checked before any of them is touched (issue 32 item 3;
// docs/user-guide.md, "Files"). A batch job must not lose a file it did not make:
//  - no output may be an input of the run (scene, polyline files, the -restart checkpoint): refused
//    even with -overwrite. One exception: the checkpoint may be the -restart file (a job chain that
//    keeps continuing the same checkpoint; it is replaced atomically);
//  - no two outputs may be the same file (-checkpoint X -o X);
//  - an existing result (the .h5 output, an existing checkpoint) is replaced only with -overwrite.
// Violations are InputErrors (exit 2) that name the option and the file.
#pragma once
#include <string>
#include <vector>

#include "strand/model/SceneDescription.hpp"

namespace strand::drivers {

struct FileRole {
  std::string role;  // how the user named it, e.g. "the scene", "-o", "-checkpoint"
  std::string path;
};

struct RunFiles {
  std::vector<FileRole> inputs;
  std::vector<FileRole> results;    // refused when they exist, unless -overwrite
  std::vector<FileRole> companions;  // written next to a result (.xmf, .csv): replaced freely
  std::string restart;               // the -restart checkpoint, if any (may also be the checkpoint)
};

// The scene's inputs: the scene file and the files it reads.
RunFiles sceneFiles(const model::SceneDescription& scene);

// Throws InputError if the files break a rule above. `overwrite`: -overwrite was given.
void checkRunFiles(const RunFiles& files, bool overwrite);

// -overwrite on the command line.
bool overwriteRequested();

// True when a and b name the same file (the same inode when both exist, else the same normalized
// absolute path; symbolic links are followed).
bool sameFile(const std::string& a, const std::string& b);

}  // namespace strand::drivers
