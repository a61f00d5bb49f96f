// libFuzzer target for the scene reader (issue 32, "a fuzz target in the project"): any byte string
// given to io::parseScene must end in a SceneDescription or an InputError ("file:line: key:
// reason"). Any other exception, a crash, an abort, a sanitizer report (the target is built with
// AddressSanitizer and UBSan), a timeout or unbounded memory is a finding. The seed corpus is
// meshes/*.yaml; tests/fuzz/CMakeLists.txt builds it with clang and runs it (docs/user-guide.md,
// "Fuzzing the scene reader").
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "strand/core/Error.hpp"
#include "strand/io/SceneReader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const strand::model::SceneDescription scene = strand::io::parseScene(text, "fuzz.yaml");
    (void)scene;
  } catch (const strand::InputError& e) {
    const std::string message = e.what();
    // a message names the file and a line, and never echoes a long value whole
    if (message.rfind("fuzz.yaml:", 0) != 0 || message.size() > 4096) {
      std::fprintf(stderr, "malformed message (%zu bytes): %.300s\n", message.size(), message.c_str());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not an InputError: %s\n", e.what());
    std::abort();
  }
  return 0;
}
