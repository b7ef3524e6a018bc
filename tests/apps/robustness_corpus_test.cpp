// The robustness corpus (tests/data/robustness/, made by tests/data/make_robustness_corpus.py):
// every file rendered by the `tandem` binary at 64 x 36 must either exit 0 with a finite,
// non-black image or exit 2 with a message naming the file — never a signal, a hang or another
// exit status. EXPECTED.tsv says which outcome each file must have and what the message says.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/image_io.h"
#include "test_util.h"

namespace tandem {
namespace {
namespace fs = std::filesystem;

struct Case {
  std::string file, expected, fragment;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.file;
}

std::vector<Case> corpus() {
  std::vector<Case> cases;
  std::ifstream in(std::string(TANDEM_SOURCE_DIR) + "/tests/data/robustness/EXPECTED.tsv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    Case c;
    std::getline(ss, c.file, '\t');
    std::getline(ss, c.expected, '\t');
    std::getline(ss, c.fragment, '\t');
    cases.push_back(c);
  }
  return cases;
}

// Runs a shell command; returns the shell's status (128 + n after signal n) and its output.
int run(const std::string& cmd, std::string* output) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) output->append(buf, n);
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

class RobustnessCorpus : public testing::TestWithParam<Case> {};

TEST_P(RobustnessCorpus, RendersOrFailsCleanly) {
  const Case& c = GetParam();
  const fs::path dir = test::scratchDir("corpus_" + fs::path(c.file).stem().string() + "_" +
                                        fs::path(c.file).extension().string().substr(1));
  const std::string input = std::string(TANDEM_SOURCE_DIR) + "/tests/data/robustness/" + c.file;
  const std::string out = (dir / "image.exr").string();
  std::string output;
  // 60 s is far beyond any file here (the slowest loads in well under a second): a hang fails.
  const int rc = run("timeout -s KILL 60 '" + std::string(TANDEM_BINARY) + "' render '" + input +
                         "' --width 64 --height 36 --threads 1 --out '" + out + "'",
                     &output);
  ASSERT_TRUE(rc == 0 || rc == 2) << c.file << ": exit " << rc << " (signal or timeout)\n"
                                  << output;
  if (c.expected == "render") {
    ASSERT_EQ(rc, 0) << c.file << "\n" << output;
    const Buffer img = loadImage(out);
    ASSERT_EQ(img.width, 64);
    ASSERT_EQ(img.height, 36);
    double sum = 0;
    float background = img.data[0];  // the sky around the model
    bool differs = false;
    for (float v : img.data) {
      ASSERT_TRUE(std::isfinite(v)) << c.file;
      sum += v;
      differs |= std::abs(v - background) > 1e-3f;
    }
    EXPECT_GT(sum / double(img.data.size()), 0.01) << c.file << ": black image";
    EXPECT_TRUE(differs) << c.file << ": nothing drawn (the image is the sky only)";
  } else {
    ASSERT_EQ(rc, 2) << c.file << "\n" << output;
    EXPECT_NE(output.find(c.file.substr(c.file.find_last_of('/') + 1)), std::string::npos)
        << "the message names the file:\n"
        << output;
    EXPECT_NE(output.find(c.fragment), std::string::npos)
        << "the message says '" << c.fragment << "':\n"
        << output;
    EXPECT_FALSE(fs::exists(out)) << "nothing written";
  }
}

std::string caseName(const testing::TestParamInfo<Case>& info) {
  std::string s = info.param.file;
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Files, RobustnessCorpus, testing::ValuesIn(corpus()), caseName);

TEST(RobustnessCorpusList, CoversEveryKindAndOutcome) {
  // The list is read from the source tree: an empty or unreadable one must fail, not pass.
  size_t gltf = 0, obj = 0, json = 0, errors = 0;
  for (const Case& c : corpus()) {
    gltf += hasExtension(c.file, ".gltf") || hasExtension(c.file, ".glb");
    obj += hasExtension(c.file, ".obj");
    json += hasExtension(c.file, ".json");
    errors += c.expected == "error";
    EXPECT_TRUE(c.expected == "render" || c.expected == "error") << c.file;
    EXPECT_TRUE(fs::exists(std::string(TANDEM_SOURCE_DIR) + "/tests/data/robustness/" + c.file))
        << c.file;
  }
  EXPECT_GE(gltf, 10u);
  EXPECT_GE(obj, 10u);
  EXPECT_GE(json, 2u);
  EXPECT_GE(errors, 10u);
}

}  // namespace
}  // namespace tandem
