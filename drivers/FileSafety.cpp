// Checks of the files a run reads and writes (FileSafety.hpp).
#include "FileSafety.hpp"

#include <petscsys.h>

#include <filesystem>
#include <system_error>

#include "strand/core/Error.hpp"

namespace strand::drivers {

namespace fs = std::filesystem;

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec), cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return ca.lexically_normal() == cb.lexically_normal();
}

RunFiles sceneFiles(const model::SceneDescription& scene) {
  RunFiles f;
  f.inputs.push_back({"the scene", scene.file});
  for (const std::string& p : scene.inputFiles) f.inputs.push_back({"a polyline file of the scene", p});
  return f;
}

bool overwriteRequested() {
  PetscBool set = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-overwrite", &set);
  return set;
}

void checkRunFiles(const RunFiles& files, bool overwrite) {
  std::vector<FileRole> outputs = files.results;
  outputs.insert(outputs.end(), files.companions.begin(), files.companions.end());
  std::vector<FileRole> inputs = files.inputs;
  if (!files.restart.empty()) inputs.push_back({"the -restart checkpoint", files.restart});
  for (const FileRole& out : outputs)
    for (const FileRole& in : inputs) {
      const bool chain = in.path == files.restart && out.role == "-checkpoint";  // continue the same checkpoint
      if (!chain && sameFile(out.path, in.path))
        throw InputError(out.role + " " + out.path + ": this output would replace " + in.role + " (" + in.path +
                         "), an input of the run; choose another file");
    }
  for (size_t i = 0; i < outputs.size(); ++i)
    for (size_t j = i + 1; j < outputs.size(); ++j)
      if (sameFile(outputs[i].path, outputs[j].path))
        throw InputError(outputs[j].role + " " + outputs[j].path + ": the same file as " + outputs[i].role +
                         "; the run writes both");
  if (overwrite) return;
  std::error_code ec;
  for (const FileRole& r : files.results) {
    if (!files.restart.empty() && sameFile(r.path, files.restart)) continue;  // the chain above
    if (fs::exists(r.path, ec))
      throw InputError(r.role + " " + r.path + ": the file exists (an earlier result?); nothing was changed. Pass "
                       "-overwrite to replace it, or choose another file");
  }
}

}  // namespace strand::drivers
