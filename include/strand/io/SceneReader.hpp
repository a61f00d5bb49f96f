// Reading a scene: YAML text -> validated model::SceneDescription (docs/scene-reference.md).
//
// The reader checks everything that can be checked from the scene alone: YAML syntax, unknown and
// duplicate keys, value types, required values, ranges, geometry that cannot be built, names and node
// indices that must exist, 2D/3D consistency. The first problem found is thrown as strand::InputError
// with the message "<file>:<line>: <dotted.key>: <reason>", for example
//   cable.yaml:12: bodies[0].section.E: must be positive (got -2e+11)
// Lines are 1-based. Every item in the result keeps its SourceMark so that later layers can point
// into the scene file too.
#pragma once
#include <string>

#include "strand/model/SceneDescription.hpp"

namespace strand::io {

// Reads and validates the scene file at `path`. A polyline `file:` is resolved relative to the
// directory of `path`. Throws strand::InputError (also when the file cannot be opened).
model::SceneDescription readScene(const std::string& path);

// Validates YAML text. `fileNameForMessages` is used in messages and as SceneDescription::file, and
// its directory is used to resolve a polyline `file:` (no directory: the working directory).
// Throws strand::InputError.
model::SceneDescription parseScene(const std::string& yamlText, const std::string& fileNameForMessages);

// Throws InputError (at the scene's `analysis` key) when the scene cannot be analysed for modes:
// rigid bodies and joints. The reader calls it for analysis: modes, `strand modes` for any scene,
// so both refuse the same way.
void requireModalScene(const model::SceneDescription& scene);

}  // namespace strand::io
