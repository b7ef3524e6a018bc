#include "pipeline/pipeline.h"

#include <algorithm>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include "core/image_io.h"
#include "core/interrupt.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

// Generated at build time from pipelines/*.json (cmake/embed_pipelines.cmake).
const std::map<std::string, std::string>& builtinPipelineSources();

namespace {
const std::map<std::string, std::string>& builtins() {
  return builtinPipelineSources();
}
}  // namespace

const std::vector<std::string>& Pipeline::builtinNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (auto& [k, v] : builtins()) n.push_back(k);
    return n;
  }();
  return names;
}

std::string Pipeline::builtinJson(const std::string& name) {
  auto it = builtins().find(name);
  return it == builtins().end() ? std::string() : it->second;
}

Pipeline Pipeline::load(const std::string& nameOrFile) {
  std::string j = builtinJson(nameOrFile);
  if (!j.empty()) return fromJson(Json::parse(j), "built-in pipeline '" + nameOrFile + "'");
  if (!std::filesystem::exists(nameOrFile)) {
    std::string known;
    for (auto& n : builtinNames()) known += (known.empty() ? "" : ", ") + n;
    throw InputError(nameOrFile, "pipeline",
                     "not a file and not a built-in pipeline (" + known + ")");
  }
  return fromJson(readJsonFile(nameOrFile), nameOrFile);
}

namespace {
// Text a reader would take for a number: what strtod reads whole ("1e400", "nan", "-inf").
bool looksNumeric(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}
}  // namespace

void setPassParam(Pass& pass, const std::string& name, const Json& value) {
  const std::vector<ParamDesc> all = pass.params();
  auto d = std::find_if(all.begin(), all.end(), [&](const ParamDesc& x) { return x.name == name; });
  auto fail = [&](const std::string& problem) { throw InputError("", name, problem); };
  if (d == all.end()) fail("unknown parameter of pass '" + pass.type() + "'");
  double v = 0;
  if (d->type == ParamType::Enum && value.is_string()) {
    auto c = std::find(d->choices.begin(), d->choices.end(), value.get<std::string>());
    if (c == d->choices.end()) fail("unknown choice '" + value.get<std::string>() + "'");
    v = double(c - d->choices.begin());
  } else if (d->type == ParamType::Bool && value.is_boolean()) {
    v = value.get<bool>() ? 1 : 0;
  } else if (value.is_number()) {
    v = value.get<double>();
  } else if (value.is_string() && looksNumeric(value.get<std::string>())) {
    // "1e400", "nan", "inf": JSON holds no such number.
    fail("'" + value.get<std::string>() + "' is not a finite number");
  } else {
    const char* expected = d->type == ParamType::Bool   ? "true or false"
                           : d->type == ParamType::Enum ? "one of its choices"
                                                        : "a number";
    fail(std::string("wrong type: expected ") + expected);
  }
  try {
    pass.setParam(name, v);
  } catch (const InputError& e) {
    fail(e.problem());
  }
}

void Pipeline::setParam(const std::string& assignment, const std::string& source) {
  // label.param=value
  size_t eq = assignment.find('='), dot = assignment.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq)
    throw InputError(source, assignment, "expected pass.param=value");
  std::string label = assignment.substr(0, dot), name = assignment.substr(dot + 1, eq - dot - 1);
  std::string text = assignment.substr(eq + 1);
  Json value = Json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;  // an enum choice given bare
  bool found = false;
  for (auto& p : passes) {
    if (p->name() != label) continue;
    found = true;
    try {
      setPassParam(*p, name, value);
    } catch (const InputError& e) {
      throw InputError(source, label + "." + name, e.problem());
    }
  }
  if (!found)
    throw InputError(source, assignment,
                     "pipeline '" + this->name + "' has no pass labelled '" + label + "'");
}

Pipeline Pipeline::fromJson(const Json& j, const std::string& source) {
  JsonFields f(j, source, "");
  Pipeline p;
  p.name = f.string("name", std::filesystem::path(source).stem().string());
  p.output = f.string("output", "output");
  const Json& passes = f.raw("passes");
  if (!passes.is_array() || passes.empty())
    f.fail("passes", "expected a non-empty array of passes");
  for (size_t i = 0; i < passes.size(); ++i) {
    std::string where = "passes[" + std::to_string(i) + "]";
    JsonFields pf(passes[i], source, where);
    std::string type = pf.string("type", "");
    std::unique_ptr<Pass> pass = createPass(type);
    if (!pass) {
      std::string known;
      for (auto& t : passTypes()) known += (known.empty() ? "" : ", ") + t;
      pf.fail("type", "unknown pass type '" + type + "' (known: " + known + ")");
    }
    pass->label = pf.string("label", type);
    pass->enabled = pf.boolean("enabled", true);
    if (pf.has("params")) {
      const Json& params = pf.raw("params");
      if (!params.is_object()) pf.fail("params", "expected an object");
      for (auto it = params.begin(); it != params.end(); ++it) {
        try {
          setPassParam(*pass, it.key(), it.value());
        } catch (const InputError& e) {
          pf.fail("params." + it.key(), e.problem());
        }
      }
    }
    for (const char* dir : {"inputs", "outputs"}) {
      if (!pf.has(dir)) continue;
      const Json& b = pf.raw(dir);
      if (!b.is_object()) pf.fail(dir, "expected an object of slot -> buffer name");
      auto slots = std::string(dir) == "inputs" ? pass->inputs() : pass->outputs();
      for (auto it = b.begin(); it != b.end(); ++it) {
        bool known = std::any_of(slots.begin(), slots.end(),
                                 [&](const BufferSlot& s) { return s.slot == it.key(); });
        if (!known)
          pf.fail(std::string(dir) + "." + it.key(), "pass '" + type + "' has no such slot");
        if (!it.value().is_string())
          pf.fail(std::string(dir) + "." + it.key(), "expected a buffer name");
        pass->bindings[it.key()] = it.value().get<std::string>();
      }
    }
    pf.finish();
    p.passes.push_back(std::move(pass));
  }
  f.finish();
  p.validate(source);
  return p;
}

bool Pipeline::reportsCounter(const std::string& name) const {
  for (const auto& p : passes)
    if (p->declaresCounter(name)) return true;
  return false;
}

void Pipeline::requireCounter(const std::string& name, const std::string& source) const {
  if (!reportsCounter(name))
    throw InputError(source, name, "no pass of pipeline '" + this->name + "' reports this counter");
}

void Pipeline::validate(const std::string& source) const {
  std::map<std::string, BufferSlot> available, produced;  // buffer -> producer's declaration
  for (const auto& p : passes)
    for (const BufferSlot& out : p->outputs()) produced[p->bufferName(out.slot)] = out;
  for (size_t i = 0; i < passes.size(); ++i) {
    const Pass& p = *passes[i];
    const std::string where = "passes[" + std::to_string(i) + "] (" + p.type() + ")";
    for (const BufferSlot& in : p.inputs()) {
      const std::string& buf = p.bufferName(in.slot);
      // A history input reads last frame's value: any pass of the pipeline may produce it.
      const auto& pool = in.history ? produced : available;
      auto it = pool.find(buf);
      if (it == pool.end()) {
        if (in.optional) continue;
        throw InputError(source, where,
                         in.history ? "history input '" + buf + "' is not produced by any pass"
                                    : "input '" + buf + "' is not produced by an earlier pass");
      }
      const BufferSlot& out = it->second;
      if (out.channels != in.channels)
        throw InputError(source, where,
                         "input '" + buf + "' has " + std::to_string(out.channels) +
                             " channels, expected " + std::to_string(in.channels));
      if (out.kind != in.kind)
        throw InputError(
            source, where,
            "input '" + buf + "' is " + kindName(out.kind) + ", expected " + kindName(in.kind));
      if (out.channels == in.channels && in.channels > 1 &&
          channelNamesOf(out) != channelNamesOf(in))
        throw InputError(source, where,
                         "input '" + buf + "' has channels (" + channelList(channelNamesOf(out)) +
                             "), expected (" + channelList(channelNamesOf(in)) + ")");
      if (out.recordType != in.recordType)
        throw InputError(
            source, where,
            "input '" + buf + "' carries " + out.recordType + ", expected " + in.recordType);
      if (in.extent.scale != Extent::Scale::Any && !(out.extent == in.extent))
        throw InputError(source, where,
                         "input '" + buf + "' has extent " + out.extent.name() + ", expected " +
                             in.extent.name());
    }
    for (const BufferSlot& out : p.outputs()) available[p.bufferName(out.slot)] = out;
  }
  if (!available.count(output))
    throw InputError(source, "output", "buffer '" + output + "' is not produced by any pass");
  checkShadows(source);
}

void Pipeline::checkShadows(const std::string& source) const {
  const Pass* shaded = nullptr;
  for (const auto& p : passes)
    if (p->enabled && p->shadesMapShadows()) shaded = p.get();
  if (!shaded) return;
  for (size_t i = 0; i < passes.size(); ++i) {
    const Pass& p = *passes[i];
    if (p.enabled && p.addsShadows())
      throw InputError(source, "passes[" + std::to_string(i) + "] (" + p.name() + ")",
                       "takes shadows from light that '" + shaded->name() +
                           "' shades with shadow maps already (set " + shaded->name() +
                           ".shadows=off, or take no shadow here: heuristic.shadows=maps, "
                           "ss_fallback.shadows=off)");
  }
}

std::vector<std::string> Pipeline::historyBuffers() const {
  std::vector<std::string> names;
  for (const auto& p : passes)
    for (const BufferSlot& in : p->inputs())
      if (in.history &&
          std::find(names.begin(), names.end(), p->bufferName(in.slot)) == names.end())
        names.push_back(p->bufferName(in.slot));
  return names;
}

FrameRequest Pipeline::request() const {
  FrameRequest r;
  for (const auto& p : passes) {
    if (!p->enabled) continue;
    FrameRequest pr;
    p->request(pr);
    if (pr.jitter) {
      r.jitterPhases = r.jitter ? std::max(r.jitterPhases, pr.jitterPhases) : pr.jitterPhases;
      r.jitter = true;
    }
  }
  return r;
}

void Pipeline::resetHistory() {
  for (auto& p : passes) p->resetHistory();
}

std::vector<std::string> Pipeline::producedBuffers() const {
  std::vector<std::string> names;
  for (const auto& p : passes)
    for (const BufferSlot& out : p->outputs()) {
      const std::string& n = p->bufferName(out.slot);
      if (out.kind != BufferKind::Record && std::find(names.begin(), names.end(), n) == names.end())
        names.push_back(n);
    }
  return names;
}

namespace {
// A disabled pass: each output takes the first (this frame's) input with the same channel count
// and extent (tonemap off shows the raw HDR), or zeros; a record output is empty.
void bypass(const Pass& p, FrameContext& ctx) {
  const std::vector<BufferSlot> ins = p.inputs();
  for (const BufferSlot& o : p.outputs()) {
    if (o.kind == BufferKind::Record) {
      ctx.output(p, o.slot).record.reset();
      continue;
    }
    auto same = std::find_if(ins.begin(), ins.end(), [&](const BufferSlot& i) {
      return !i.history && i.channels == o.channels && ctx.has(p.bufferName(i.slot));
    });
    const Buffer* src = same != ins.end() ? &ctx.input(p.bufferName(same->slot)) : nullptr;
    const bool fits = src && (o.extent.scale == Extent::Scale::Any || (o.extent == same->extent));
    Buffer& out = ctx.output(p, o.slot, src ? src->width : 0, src ? src->height : 0);
    if (fits && src->sameShape(out))
      out.data = src->data;
    else
      out.fill(0.0f);
  }
}

// Checking mode (FrameContext::isolatePasses): `run` sees only the buffers `p` declares, this
// frame's and last frame's, and may leave behind only them; the rest is put back afterwards.
template <class Run>
void runIsolated(const Pass& p, FrameContext& ctx, Run&& run) {
  std::set<std::string> mine, myHistory;
  for (const BufferSlot& s : p.inputs())
    (s.history ? myHistory : mine).insert(p.bufferName(s.slot));
  for (const BufferSlot& s : p.outputs()) mine.insert(p.bufferName(s.slot));
  const auto setAside = [](std::map<std::string, Buffer>& from, const std::set<std::string>& keep) {
    std::map<std::string, Buffer> aside;
    for (auto it = from.begin(); it != from.end();) {
      const auto next = std::next(it);
      if (!keep.count(it->first)) aside.insert(from.extract(it));
      it = next;
    }
    return aside;
  };
  std::map<std::string, Buffer> others = setAside(ctx.buffers, mine);
  std::map<std::string, Buffer> otherHistory = setAside(ctx.history, myHistory);
  const auto putBack = [&] {
    ctx.buffers.merge(others);
    ctx.history.merge(otherHistory);
  };
  try {
    run();
  } catch (...) {
    putBack();
    throw;
  }
  for (const auto& [name, buffer] : ctx.buffers)
    if (!mine.count(name)) {
      putBack();
      throw std::logic_error("pass '" + p.name() + "' wrote buffer '" + name +
                             "', which it does not declare");
    }
  putBack();
}
}  // namespace

namespace {
// A frame's timing rows in the order of its passes. A batched GPU pass's rows (its GPU time, its
// parts, its rays) are known only once its batch ran: it reserves its place.
struct FrameRows {
  std::vector<std::vector<PassTiming>> groups;
  void add(PassTiming t) { groups.push_back({std::move(t)}); }
  size_t reserve() {
    groups.emplace_back();
    return groups.size() - 1;
  }
  std::vector<PassTiming> all() && {
    std::vector<PassTiming> out;
    for (auto& g : groups)
      for (PassTiming& t : g) out.push_back(std::move(t));
    return out;
  }
};

// A move between host and device, as its own timing row with its bytes.
void moveToHost(const std::string& name, FrameContext& ctx, FrameRows& rows) {
  auto it = ctx.buffers.find(name);
  if (it == ctx.buffers.end()) return;
  const auto t0 = Clock::now();
  const size_t bytes = ctx.gpu->download(name, it->second);
  if (bytes) rows.add({"download:" + name, msSince(t0), 0, double(bytes)});
}

// The same move recorded in the open batch, done (and its row filled) when the batch has run.
// `history`: last frame's value (ctx.history, its device copy under historyKey).
void queueToHost(const std::string& name, FrameContext& ctx, FrameRows& rows,
                 bool history = false) {
  std::map<std::string, Buffer>& where = history ? ctx.history : ctx.buffers;
  const std::string key = history ? historyKey(name) : name;
  auto it = where.find(name);
  if (it == where.end() || !ctx.gpu->deviceNewer(key)) return;
  const size_t slot = rows.reserve();
  const double bytes = double(it->second.data.size() * sizeof(float));
  ctx.gpu->queueDownload(key, it->second, [&rows, slot, key, bytes](double ms) {
    rows.groups[slot].push_back({"download:" + key, ms, 0, bytes});
  });
}

// Before a pass: its declared inputs where it runs (this frame's buffers, and for a GPU pass
// last frame's value of its history inputs, under historyKey; records never move).
void moveInputs(const Pass& p, FrameContext& ctx, bool onGpu, FrameRows& rows) {
  for (const BufferSlot& in : p.inputs()) {
    if (in.history) {  // last frame's value: moved to where the pass reads it
      const std::string& name = p.bufferName(in.slot);
      auto it = ctx.history.find(name);
      const std::string key = historyKey(name);
      if (it == ctx.history.end()) continue;
      if (!onGpu) {
        const auto t0 = Clock::now();
        const size_t bytes = ctx.gpu->download(key, it->second);
        if (bytes) rows.add({"download:" + key, msSince(t0), 0, double(bytes)});
        continue;
      }
      if (ctx.gpu->onDevice(key)) continue;
      const auto t0 = Clock::now();
      const size_t bytes = ctx.gpu->upload(key, it->second);
      rows.add({"upload:" + key, msSince(t0), 0, double(bytes)});
      continue;
    }
    const std::string& name = p.bufferName(in.slot);
    auto it = ctx.buffers.find(name);
    if (it == ctx.buffers.end() || it->second.kind == BufferKind::Record) continue;
    if (!onGpu) {
      if (ctx.gpu->deviceNewer(name)) moveToHost(name, ctx, rows);
      continue;
    }
    if (ctx.gpu->onDevice(name)) continue;
    const auto t0 = Clock::now();
    const size_t bytes = ctx.gpu->upload(name, it->second);
    rows.add({"upload:" + name, msSince(t0), 0, double(bytes)});
  }
}

// Records the pass's kernels into the open batch between two timestamps. Its rows (GPU time,
// the host's time recording, its parts and rays) and its own afterSubmit work come once the
// batch has run: that work runs with the pass's rays and parts in the context, as if alone.
// Whether the pass left such work (which may write its records).
bool recordOnGpu(Pass& p, FrameContext& ctx, FrameRows& rows) {
  GpuFrame& gpu = *ctx.gpu;
  gpu.open();
  GpuCommands& cmd = gpu.commands();
  const size_t first = gpu.afterSubmitCount();
  const auto t0 = Clock::now();
  cmd.barrier();  // what the batch's earlier passes wrote is visible
  const uint32_t a = cmd.timestamp();
  p.executeGpu(ctx);
  const uint32_t b = cmd.timestamp();
  const double hostMs = msSince(t0);
  const size_t slot = rows.reserve();
  std::vector<std::function<void()>> work = gpu.takeAfterSubmit(first);
  const bool deferred = !work.empty();
  gpu.afterSubmit([&p, &ctx, &rows, &cmd, slot, a, b, hostMs, rays = ctx.passRays,
                   parts = ctx.passParts, work = std::move(work)]() mutable {
    const double otherRays = ctx.passRays;
    std::vector<PassTiming> otherParts = std::move(ctx.passParts);
    ctx.passRays = rays;
    ctx.passParts = std::move(parts);
    for (auto& f : work) f();
    // A GPU pass's row is its GPU time (timestamps); its part "host" is the wall time of
    // recording it. Parts come after their pass and are not added to the frame total again.
    std::vector<PassTiming>& g = rows.groups[slot];
    g.push_back({p.name(), cmd.activeMs(a, b), ctx.passRays});
    g.push_back({p.name() + "/host", hostMs, 0});
    for (PassTiming& part : ctx.passParts)
      g.push_back({p.name() + "/" + part.name, part.ms, part.rays});
    ctx.passRays = otherRays;
    ctx.passParts = std::move(otherParts);
  });
  return deferred;
}

// Whether a pass reads this frame a record that a batched pass writes once its batch has run.
bool readsPendingRecord(const Pass& p, const std::set<std::string>& pendingRecords) {
  for (const BufferSlot& in : p.inputs())
    if (!in.history && pendingRecords.count(p.bufferName(in.slot))) return true;
  return false;
}
// At the frame's end, into its last batch: what the caller reads comes back (with keepAllOutputs
// and allToHost everything; else the output, unless outputToHost is off, and what it wants; the
// rest stays on the device, moved only if a host pass or Renderer::fetch reads it later), and
// history the device holds is copied to its history key (the next frame's GPU passes read it
// there; a CPU pass that reads it moves it first). The history buffers so copied.
std::set<std::string> finishOnGpu(FrameContext& ctx, const std::string& output,
                                  const std::vector<std::string>& history, FrameRows& rows) {
  for (const std::string& name : ctx.gpu->deviceOnly())
    if ((ctx.keepAllOutputs && ctx.allToHost) || (name == output && ctx.outputToHost) ||
        ctx.wanted.count(name))
      queueToHost(name, ctx, rows);
  std::set<std::string> copied;
  for (const std::string& name : history) {
    auto it = ctx.buffers.find(name);
    if (it == ctx.buffers.end() || !ctx.gpu->onDevice(name)) continue;
    const bool hostCurrent = !ctx.gpu->deviceNewer(name);  // came back, or was uploaded
    ctx.gpu->copyOnDevice(name, historyKey(name), it->second.data.size() * sizeof(float),
                          hostCurrent);
    copied.insert(name);
  }
  return copied;
}

// What the next frame reads as last frame's value (copied: the buffer stays readable); what only
// the device holds (`onDevice`, newer there) is kept on the host as its shape. Whether any was.
bool keepHistory(FrameContext& ctx, const std::vector<std::string>& history,
                 const std::set<std::string>& onDevice) {
  bool any = false;
  for (const std::string& name : history) {
    auto it = ctx.buffers.find(name);
    if (it == ctx.buffers.end()) continue;
    any = true;
    if (onDevice.count(name) && ctx.gpu->deviceNewer(historyKey(name))) {
      Buffer& h = ctx.history[name];
      if (!h.sameShape(it->second))
        h = Buffer(it->second.width, it->second.height, it->second.channels, 0.0f, it->second.kind);
      continue;
    }
    ctx.history[name] = it->second;
    // A new value, moved again when a GPU pass reads it (unless the device copied it too).
    if (ctx.gpu && !onDevice.count(name)) ctx.gpu->hostWrote(historyKey(name));
  }
  return any;
}
}  // namespace

FrameTimings Pipeline::execute(FrameContext& ctx) {
  pollInterrupt();  // before a frame: a stop never leaves one half drawn
  FrameTimings ft;
  auto frameStart = Clock::now();
  checkShadows("pipeline '" + name + "'");  // an edit since loading may have doubled them
  ++ctx.serial;
  ctx.counters.clear();
  // An edit of an invalidating parameter starts every pass's history over.
  for (auto& p : passes)
    if (p->historyInvalidated) {
      ctx.historyReset = true;
      p->historyInvalidated = false;
    }
  if (ctx.historyReset) {
    ctx.history.clear();
    resetHistory();
  }
  ctx.consumed = {output};
  for (const auto& p : passes)
    for (const BufferSlot& in : p->inputs()) ctx.consumed.insert(p->bufferName(in.slot));
  FrameRows rows;
  double submitMs = 0;                   // the host's wait for the frame's batches
  std::set<std::string> pendingRecords;  // records the open batch's passes write once it has run
  std::set<std::string> deviceHistory;   // history the device copied to its history key
  const auto flush = [&] {
    submitMs += ctx.gpu->flush();
    pendingRecords.clear();
  };
  try {
    for (size_t i = 0; i < passes.size(); ++i) {
      Pass* p = passes[i].get();
      const bool onGpu = ctx.gpu && p->enabled && p->hasGpu();
      // The host sees what the batch computed before a CPU pass runs (what it and the CPU passes
      // after it read from the device, this frame's and last frame's, coming back in that
      // batch), or before a GPU pass reads a record it writes.
      if (ctx.gpu && !onGpu)
        for (size_t j = i; j < passes.size(); ++j)
          if (!(passes[j]->enabled && passes[j]->hasGpu()))
            for (const BufferSlot& in : passes[j]->inputs())
              queueToHost(passes[j]->bufferName(in.slot), ctx, rows, in.history);
      if (ctx.gpu && (!onGpu || readsPendingRecord(*p, pendingRecords))) flush();
      ctx.passRays = 0;
      ctx.passParts.clear();
      if (ctx.gpu) moveInputs(*p, ctx, onGpu, rows);
      auto t0 = Clock::now();
      bool deferred = false;  // a GPU pass's work left for when the batch has run
      const auto run = [&] {
        if (onGpu) {
          deferred = recordOnGpu(*p, ctx, rows);
          if (ctx.isolatePasses) flush();
        } else if (p->enabled) {
          p->execute(ctx);
        } else {
          bypass(*p, ctx);
        }
      };
      if (ctx.isolatePasses)
        runIsolated(*p, ctx, run);
      else
        run();
      if (onGpu) {
        if (deferred && !ctx.isolatePasses)
          for (const BufferSlot& o : p->outputs())
            if (o.kind == BufferKind::Record) pendingRecords.insert(p->bufferName(o.slot));
        continue;  // its rows come with the batch
      }
      const std::string label = p->name();
      rows.add({label, msSince(t0), ctx.passRays});
      for (PassTiming& part : ctx.passParts)
        rows.add({label + "/" + part.name, part.ms, part.rays});
    }
    if (ctx.gpu) {
      deviceHistory = finishOnGpu(ctx, output, historyBuffers(), rows);
      flush();
      if (submitMs > 0) rows.add({"gpu_submit", submitMs, 0});
    }
  } catch (...) {
    // Nothing the batch was to compute can be trusted; history only the device held is lost
    // with it, so the next frame starts its history over.
    bool lost = false;
    if (ctx.gpu)
      for (const std::string& name : historyBuffers())
        lost |= ctx.gpu->deviceNewer(historyKey(name));
    if (ctx.gpu && ctx.gpu->abandon() && lost) ctx.historyReset = true;
    throw;
  }
  auto h0 = Clock::now();
  const bool any = keepHistory(ctx, historyBuffers(), deviceHistory);
  if (any) rows.add({"history", msSince(h0), 0});
  ctx.historyReset = false;
  ft.passes = std::move(rows).all();
  ft.totalMs = msSince(frameStart);
  return ft;
}

Json Pipeline::toJson() const {
  Json j;
  j["name"] = name;
  j["output"] = output;
  j["passes"] = Json::array();
  for (const auto& p : passes) {
    Json pj;
    pj["type"] = p->type();
    if (p->label != p->type()) pj["label"] = p->label;
    if (!p->enabled) pj["enabled"] = false;
    // Typed as a user would write them, so fromJson(toJson()) gives the same pipeline.
    Json params = Json::object();
    for (const ParamDesc& d : p->params()) {
      const double v = p->param(d.name);
      if (d.type == ParamType::Bool)
        params[d.name] = v != 0;
      else if (d.type == ParamType::Enum)
        params[d.name] = d.choices.at(size_t(v));
      else if (d.type == ParamType::Int)
        params[d.name] = int64_t(v);
      else
        params[d.name] = v;
    }
    if (!params.empty()) pj["params"] = params;
    if (!p->bindings.empty()) {
      Json in = Json::object(), out = Json::object();
      for (const BufferSlot& s : p->inputs())
        if (p->bindings.count(s.slot)) in[s.slot] = p->bindings.at(s.slot);
      for (const BufferSlot& s : p->outputs())
        if (p->bindings.count(s.slot)) out[s.slot] = p->bindings.at(s.slot);
      if (!in.empty()) pj["inputs"] = in;
      if (!out.empty()) pj["outputs"] = out;
    }
    j["passes"].push_back(pj);
  }
  return j;
}

}  // namespace tandem
