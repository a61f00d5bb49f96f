// Subcommands of the `strand` executable. Each returns a process exit code (strand::ExitCode).
#pragma once
#include <string>

#include "strand/model/SceneDescription.hpp"

namespace strand::drivers {

enum class RunMode { SceneAnalysis, ForceModes };

// `strand run SCENE` (RunMode::SceneAnalysis) and `strand modes SCENE` (RunMode::ForceModes).
int runScene(const char* scenePath, RunMode mode);

// `strand sweep SCENE`: the scene's `sweep` of the linearized modes (SweepCommand.cpp).
int runSweepScene(const char* scenePath);

extern const char* kVersion;
// The output file: -o FILE, else the scene's output.file, else <scene stem>.h5 in the working directory.
std::string outputPath(const model::SceneDescription& scene);

}  // namespace strand::drivers
