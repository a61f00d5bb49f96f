// requirement (issue 32 items 9 and 10): the scene reader takes nothing that is wrong but looks
// valid. Integers are decimal (010 was read as octal 8); a second YAML document is refused, not
// ignored; every text value is UTF-8 without control characters (an invalid body name broke the
// XDMF file); a body or rigid-body name with '/' or ':' is refused with file:line (before: by the
// output writer, without a line); `strand sweep` without a sweep section names a line (checked in
// regression_reliability); no message echoes a long value whole (a 2 MB value was echoed); and
// files are read with a bound: a device, a pipe or an oversized file is not a scene or a polyline
// file (/dev/zero was read without end).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "strand/core/Error.hpp"
#include "strand/io/SceneReader.hpp"

namespace fs = std::filesystem;
using namespace strand;
using strand::io::parseScene;
using strand::io::readScene;

namespace {

const std::string kScene =                                           // line
    "analysis: static\n"                                             // 1
    "dimension: 2\n"                                                 // 2
    "bodies:\n"                                                      // 3
    "  - name: cable\n"                                              // 4
    "    element: AncfCable2d\n"                                     // 5
    "    elements: 20\n"                                             // 6
    "    geometry: {kind: line, start: [0, 0], end: [2, 0]}\n"       // 7
    "    section: {E: 2.1e11, A: 7.85e-5, I: 4.91e-10, rho: 7850}\n" // 8
    "supports:\n"                                                    // 9
    "  - {body: cable, node: 0, type: clamped}\n";                   // 10

std::string edit(const std::string& text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return pos == std::string::npos ? text : text.substr(0, pos) + to + text.substr(pos + from.size());
}

// The InputError message of parsing `yaml` as scene.yaml, "" when it is accepted.
std::string refusal(const std::string& yaml) {
  try {
    parseScene(yaml, "scene.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SceneReaderInput, IntegersAreDecimalAndALeadingZeroIsRefused) {
  EXPECT_EQ(parseScene(kScene, "scene.yaml").bodies[0].elements, 20);
  const std::string octal = refusal(edit(kScene, "elements: 20", "elements: 010"));
  EXPECT_EQ(octal.rfind("scene.yaml:6: bodies[0].elements: expected an integer (got '010'): a leading 0", 0), 0u)
      << octal;
  for (const char* bad : {"0x10", "0o10", "1e3", "+", "12abc"}) {
    const std::string why = refusal(edit(kScene, "elements: 20", std::string("elements: ") + bad));
    EXPECT_EQ(why.rfind("scene.yaml:6: bodies[0].elements: expected an integer", 0), 0u) << bad << ": " << why;
  }
  EXPECT_EQ(parseScene(edit(kScene, "elements: 20", "elements: +7"), "scene.yaml").bodies[0].elements, 7);
  EXPECT_EQ(parseScene(edit(kScene, "node: 0,", "node: -0,"), "scene.yaml").supports[0].at.node, 0);
}

TEST(SceneReaderInput, ASecondDocumentIsRefused) {
  const std::string why = refusal(kScene + "---\nanalysis: modes\n");
  EXPECT_EQ(why, "scene.yaml:12: (document): a second YAML document ('---') is not read; a scene is one document");
  EXPECT_EQ(refusal("---\n" + kScene + "...\n"), "");  // one document with its markers is fine
  // found by tests/fuzz: yaml-cpp's LoadAll never returned on a stray ',' (an endless stream of
  // empty documents); the reader reads at most two documents
  EXPECT_NE(refusal(",\n"), "");
  EXPECT_NE(refusal(", a:\n  b: 1\n"), "");
}

TEST(SceneReaderInput, TextIsUtf8WithoutControlCharactersAndNamesFitTheOutput) {
  std::string why = refusal(edit(kScene, "name: cable", "name: cab\xff" "le"));  // a raw byte, not a YAML escape
  EXPECT_EQ(why, "scene.yaml:4: bodies[0].name: not UTF-8 text (byte 0xff at offset 3)");
  why = refusal(edit(kScene, "name: cable", "name: cab\xed\xa0\x80" "le"));  // a UTF-16 surrogate
  EXPECT_EQ(why, "scene.yaml:4: bodies[0].name: not UTF-8 text (byte 0xed at offset 3)");
  why = refusal(edit(kScene, "name: cable", "name: \"cab\\x01le\""));
  EXPECT_EQ(why, "scene.yaml:4: bodies[0].name: control character 0x01 at offset 3");
  const std::string accented = "c\xc3\xa2" "ble";  // U+00E2
  EXPECT_EQ(refusal(edit(edit(kScene, "name: cable", "name: " + accented), "body: cable", "body: " + accented)), "");
  why = refusal(edit(edit(kScene, "name: cable", "name: a/b"), "body: cable", "body: a/b"));
  EXPECT_EQ(why, "scene.yaml:4: bodies[0].name: 'a/b' cannot name an output group: no '/' or ':', not '.' or '..'");
  why = refusal(edit(edit(kScene, "name: cable", "name: '..'"), "body: cable", "body: '..'"));
  EXPECT_NE(why.find("cannot name an output group"), std::string::npos) << why;
}

TEST(SceneReaderInput, MessagesDoNotEchoLongValues) {
  const std::string value(2 << 20, 'x');
  std::string why = refusal(edit(kScene, "element: AncfCable2d", "element: " + value));
  EXPECT_LT(why.size(), 300u);
  EXPECT_NE(why.find("unknown element type 'xxxx"), std::string::npos) << why.substr(0, 300);
  EXPECT_NE(why.find("(2097152 bytes)"), std::string::npos) << why.substr(0, 300);
  why = refusal(edit(kScene, "  - name: cable", "  - " + value + ": 1\n    name: cable"));
  EXPECT_LT(why.size(), 2500u);
}

TEST(SceneReaderInput, FilesAreReadWithABound) {
  std::string why;
  try {
    readScene("/dev/zero");
  } catch (const InputError& e) {
    why = e.what();
  }
  EXPECT_EQ(why, "/dev/zero:0: (file): not a regular file; a scene is a YAML text file");
  const fs::path dir = fs::temp_directory_path() / ("strand-reader-input-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "big.yaml") << std::string((16 << 20) + 1, '#');
  try {
    readScene((dir / "big.yaml").string());
  } catch (const InputError& e) {
    why = e.what();
  }
  EXPECT_NE(why.find("big.yaml:0: (file): 16777217 bytes, more than a scene may have (16 MB)"), std::string::npos) << why;
  std::ofstream(dir / "line.yaml") << edit(kScene, "{kind: line, start: [0, 0], end: [2, 0]}", "{kind: polyline, file: /dev/zero}");
  try {
    readScene((dir / "line.yaml").string());
  } catch (const InputError& e) {
    why = e.what();
  }
  EXPECT_NE(why.find("line.yaml:7: bodies[0].geometry.file: '/dev/zero' is not a regular file"), std::string::npos)
      << why;
  fs::remove_all(dir);
}
