// A pipeline: an ordered list of passes wired through named buffers, described in JSON
// (built-ins ship in pipelines/ and are compiled in). Wiring is checked before the first frame;
// every pass is timed every frame.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/json_fields.h"
#include "core/profiler.h"
#include "pipeline/pass.h"

namespace tandem {

struct FrameContext;

// The explicit list of pass types (no static registration).
std::unique_ptr<Pass> createPass(const std::string& type);
const std::vector<std::string>& passTypes();

// Sets one parameter from a JSON value, checked against the pass's ParamDesc; throws InputError
// (field = parameter name) on an unknown name, wrong type or out-of-range value.
void setPassParam(Pass& pass, const std::string& name, const Json& value);

class Pipeline {
 public:
  std::string name;
  std::string output = "output";  // the buffer written as the final image
  std::vector<std::unique_ptr<Pass>> passes;

  static Pipeline fromJson(const Json& j, const std::string& source);
  // A built-in name (deferred, deferred-rt-gbuffer) or a path to a pipeline JSON file.
  static Pipeline load(const std::string& nameOrFile);
  static const std::vector<std::string>& builtinNames();
  static std::string builtinJson(const std::string& name);  // empty when unknown

  // Every input is produced by an earlier pass (a history input: by any pass) with the same
  // channel count, kind and extent (an optional input may be produced by none), and the output
  // buffer exists. Throws InputError naming `source`, the pass and the buffer.
  void validate(const std::string& source) const;
  // InputError when a pass shades with shadow maps and another takes shadows from the same light
  // again (validate, the CLI after its --set assignments, and each frame check it).
  void checkShadows(const std::string& source) const;
  // Buffers some pass reads as last frame's value (kept by execute() for the next frame).
  std::vector<std::string> historyBuffers() const;
  // What the enabled passes ask of the next frame (jitter).
  FrameRequest request() const;
  // Every pass forgets its own history (the frame context's history buffers are cleared too
  // when execute() sees ctx.historyReset).
  void resetHistory();
  // Buffer names produced by the passes, in order (for --aov listings and the viewer); records,
  // which have no pixels, are not listed.
  std::vector<std::string> producedBuffers() const;

  // Whether some pass reports counter `name` (Pass::counters()).
  bool reportsCounter(const std::string& name) const;
  // A reader's check when it loads the pipeline: throws InputError naming `source` and the
  // counter when no pass of this pipeline declares it.
  void requireCounter(const std::string& name, const std::string& source) const;

  // Sets a parameter from "label.param=value" (value as JSON, or a bare enum choice) on every
  // pass with that label; throws InputError naming `source` and the assignment.
  void setParam(const std::string& assignment, const std::string& source);

  FrameTimings execute(FrameContext& ctx);
  Json toJson() const;  // with current parameter values
};

}  // namespace tandem
