// A pass declares its inputs, outputs and parameters before it runs, so a pipeline can check
// its wiring when it loads, the viewer can generate widgets, and docs/passes.md can be derived.
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/buffer.h"
#include "core/json_fields.h"

namespace tandem {

struct FrameContext;

enum class ParamType { Float, Int, Bool, Enum };

// One parameter, described once: name, type, default, range, doc (and choices for enums).
struct ParamDesc {
  std::string name{};
  ParamType type = ParamType::Float;
  double defaultValue = 0, min = 0, max = 1;
  std::string doc{};
  std::vector<std::string> choices{};  // Enum: value is the index into choices
  bool invalidatesHistory = false;     // an edit resets every pass's history (a new picture)
};

// A figure a pass reports every frame it runs (FrameContext::report): declared with a short doc
// so `tandem passes` lists it and a reader asking for a name no pass reports fails when the
// pipeline loads (Pipeline::requireCounter), not with a silent zero.
struct CounterDesc {
  std::string name;  // the full name readers use ("heuristic/selected")
  std::string doc{};
};

// What a pass asks of the next frame before it is rendered (the renderer merges every enabled
// pass's request).
struct FrameRequest {
  bool jitter = false;   // sub-pixel projection jitter from the Halton (2, 3) sequence
  int jitterPhases = 8;  // length of the jitter cycle (the largest asked for wins)
};

class Pass {
 public:
  virtual ~Pass() = default;
  virtual std::string type() const = 0;
  virtual std::string description() const = 0;
  virtual std::vector<BufferSlot> inputs() const { return {}; }
  virtual std::vector<BufferSlot> outputs() const { return {}; }
  virtual std::vector<ParamDesc> params() const { return {}; }
  // The counters the pass reports (default: none); reporting any other is a logic_error.
  virtual std::vector<CounterDesc> counters() const { return {}; }
  bool declaresCounter(const std::string& name) const;
  virtual void execute(FrameContext& ctx) = 0;
  // A GPU implementation beside the CPU one (same slots, settings and counters): with a GPU
  // (ctx.gpu) the pipeline moves the declared inputs to the device and runs executeGpu, which
  // records its kernels into ctx.gpu's commands (FrameContext::deviceInput / deviceOutput); the
  // pipeline submits them and times them with GPU timestamps.
  virtual bool hasGpu() const { return false; }
  // When hasGpu() depends on the settings: the condition, in the pass's parameter names, as a
  // phrase ("with ...", "unless ...") completing "runs on the GPU too" (docs).
  virtual std::string gpuCondition() const { return ""; }
  virtual void executeGpu(FrameContext& ctx) { execute(ctx); }
  // Where the frame's shadows come from (Pipeline::checkShadows keeps a light from being shadowed
  // twice): a pass whose hdr is shaded with the shadow maps already, and a pass that takes a
  // shadow from light it holds unshadowed (eq. 4's L - (1 - S): traced or fallback shadows).
  virtual bool shadesMapShadows() const { return false; }
  virtual bool addsShadows() const { return false; }
  // Asks for what the next frame needs (default: nothing).
  virtual void request(FrameRequest&) const {}
  // Forget everything carried from earlier frames (camera cut, resize, scene reload, pipeline
  // switch, an invalidating parameter edit). Declared history inputs are dropped by the
  // pipeline; this is for state a pass keeps itself.
  virtual void resetHistory() {}
  // Declaration of a slot by name (null when the pass has no such slot).
  std::optional<BufferSlot> outputSlot(const std::string& slot) const;
  std::optional<BufferSlot> inputSlot(const std::string& slot) const;

  // Parameter values by name, validated against params(): for generic readers (the viewer, the
  // docs, --set, tests). A pass reads its typed settings (SettingsPass, param_table.h).
  double param(const std::string& name) const;
  void setParam(const std::string& name, double value);  // throws on unknown name or range
  void resetParams();

  // Slot -> buffer name in the frame context (defaults to the slot name).
  std::map<std::string, std::string> bindings;
  const std::string& bufferName(const std::string& slot) const;
  std::string label;  // instance name for timings (defaults to type)
  // The label, or the type when the pipeline gave none: what timing rows, counters and --set
  // call this pass.
  std::string name() const { return label.empty() ? type() : label; }
  // A disabled pass is bypassed: each output takes the first input with the same channel count
  // (tonemap off shows the raw HDR), or zeros when there is none.
  bool enabled = true;
  // Set when a parameter marked invalidatesHistory was edited; the pipeline resets and clears it.
  bool historyInvalidated = false;

 protected:
  // Told of every accepted value and of a reset, so typed settings (param_table.h) follow.
  virtual void onParamSet(const std::string&, double) {}
  virtual void onParamsReset() {}

 private:
  std::map<std::string, double> values_;
};

}  // namespace tandem
