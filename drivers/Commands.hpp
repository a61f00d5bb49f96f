// Subcommands of the `strand` executable. Each returns a process exit code (strand::ExitCode).
#pragma once

namespace strand::drivers {

enum class RunMode { SceneAnalysis, ForceModes };

// `strand run SCENE` (RunMode::SceneAnalysis) and `strand modes SCENE` (RunMode::ForceModes).
int runScene(const char* scenePath, RunMode mode);

}  // namespace strand::drivers
