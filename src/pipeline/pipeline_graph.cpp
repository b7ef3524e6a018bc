#include "pipeline/pipeline_graph.h"

#include <map>
#include <set>
#include <sstream>

namespace tandem {

namespace {

std::string slotText(const BufferSlot& s) {
  if (s.kind == BufferKind::Record) return "record " + s.recordType;
  std::ostringstream t;
  t << s.channels << " " << kindName(s.kind);
  const std::vector<std::string> names = channelNamesOf(s);
  if (!names.empty()) t << ": " << channelList(names);
  if (!(s.extent == Extent::frame())) t << ", " << s.extent.name();
  return t.str();
}

}  // namespace

std::string describePipeline(const Pipeline& p) {
  std::ostringstream o;
  o << "pipeline " << p.name << ": " << p.passes.size() << " passes, output '" << p.output << "'\n";
  for (size_t i = 0; i < p.passes.size(); ++i) {
    const Pass& pass = *p.passes[i];
    o << "\n" << i + 1 << ". " << pass.name();
    if (pass.name() != pass.type()) o << " (" << pass.type() << ")";
    if (!pass.enabled) o << " [disabled]";
    o << "\n";
    for (const BufferSlot& in : pass.inputs()) {
      o << "     reads  " << pass.bufferName(in.slot) << " (" << slotText(in);
      if (in.history) o << "; last frame's";
      if (in.optional) o << "; optional";
      o << ")\n";
    }
    for (const BufferSlot& out : pass.outputs())
      o << "     writes " << pass.bufferName(out.slot) << " (" << slotText(out) << ")\n";
  }
  const std::vector<std::string> history = p.historyBuffers();
  if (!history.empty()) {
    o << "\nhistory (kept for the next frame):";
    for (const std::string& h : history) o << " " << h;
    o << "\n";
  }
  return o.str();
}

std::string pipelineDot(const Pipeline& p) {
  std::ostringstream o;
  o << "digraph \"" << p.name << "\" {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n";
  std::set<std::string> buffers;
  auto buffer = [&](const std::string& name, const BufferSlot& s) {
    if (!buffers.insert(name).second) return;
    o << "  \"b:" << name << "\" [shape=ellipse, label=\"" << name << "\\n"
      << slotText(s) << "\"" << (name == p.output ? ", style=bold" : "") << "];\n";
  };
  for (size_t i = 0; i < p.passes.size(); ++i) {
    const Pass& pass = *p.passes[i];
    o << "  p" << i << " [shape=box, style=filled, fillcolor=\"#dde6f0\", label=\"" << pass.name();
    if (pass.name() != pass.type()) o << "\\n(" << pass.type() << ")";
    o << "\"];\n";
    for (const BufferSlot& out : pass.outputs()) {
      buffer(pass.bufferName(out.slot), out);
      o << "  p" << i << " -> \"b:" << pass.bufferName(out.slot) << "\";\n";
    }
  }
  for (size_t i = 0; i < p.passes.size(); ++i) {
    const Pass& pass = *p.passes[i];
    for (const BufferSlot& in : pass.inputs()) {
      const std::string& name = pass.bufferName(in.slot);
      if (!buffers.count(name)) continue;  // an optional input nothing produces
      o << "  \"b:" << name << "\" -> p" << i;
      if (in.history)
        o << " [style=dashed, label=\"last frame\"]";
      else if (in.optional)
        o << " [style=dotted]";
      o << ";\n";
    }
  }
  o << "}\n";
  return o.str();
}

}  // namespace tandem
