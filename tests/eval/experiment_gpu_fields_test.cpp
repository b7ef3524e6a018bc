// An experiment's "gpu" fields: the papers' real-time sizes replace the file's own only where a
// hardware GPU renders; a field the experiment lacks, or a "gpu" that is not an object, is an
// error naming the file and the field.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/error.h"
#include "eval/experiments/experiment_runner.h"

namespace tandem {
namespace {

nlohmann::json experiment() {
  return nlohmann::json::parse(
      R"({"runner": "hybrid-dof", "width": 960, "height": 540, "sweepWidth": 480,
          "gpu": {"width": 1920, "height": 1080}})");
}

TEST(ExperimentGpuFields, ReplaceTheSizesOnlyOnAHardwareGpu) {
  nlohmann::json cpu = experiment(), gpu = experiment();
  applyGpuFields(cpu, "x.json", false);
  applyGpuFields(gpu, "x.json", true);
  EXPECT_EQ(cpu["width"], 960);
  EXPECT_EQ(cpu["height"], 540);
  EXPECT_EQ(gpu["width"], 1920);
  EXPECT_EQ(gpu["height"], 1080);
  EXPECT_EQ(gpu["sweepWidth"], 480);  // what "gpu" does not name stays
  EXPECT_FALSE(cpu.contains("gpu"));  // the runners never see it
  EXPECT_FALSE(gpu.contains("gpu"));
}

TEST(ExperimentGpuFields, BadFieldsAreErrorsNamingThem) {
  const auto message = [](const char* text) {
    nlohmann::json j = nlohmann::json::parse(text);
    try {
      applyGpuFields(j, "x.json", false);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string typo = message(R"({"width": 1, "gpu": {"widht": 2}})");
  EXPECT_NE(typo.find("x.json"), std::string::npos) << typo;
  EXPECT_NE(typo.find("gpu.widht"), std::string::npos) << typo;
  const std::string runner = message(R"({"runner": "taa", "gpu": {"runner": "sweep"}})");
  EXPECT_NE(runner.find("gpu.runner"), std::string::npos) << runner;
  const std::string notObject = message(R"({"width": 1, "gpu": 5})");
  EXPECT_NE(notObject.find("gpu"), std::string::npos) << notObject;
  EXPECT_NE(notObject.find("expected an object"), std::string::npos) << notObject;
}

// Every built-in experiment's "gpu" fields name fields it has.
TEST(ExperimentGpuFields, BuiltInExperimentsNameTheirOwnFields) {
  for (const auto& [name, title] : listExperiments()) {
    std::ifstream in(resolveExperiment(name));
    nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_NO_THROW(applyGpuFields(j, name, true)) << name;
  }
}

}  // namespace
}  // namespace tandem
