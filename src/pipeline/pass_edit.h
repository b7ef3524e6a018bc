// Typed edits of a pipeline's passes, for code that configures pipelines (the experiments, the
// reference cache): each pass of the given type named `name` (its label, else its type) gets
// its settings struct changed in C++, so a misspelt member does not compile, and set back through
// its parameter table (SettingsPass::assign), which checks ranges as --set does.
#pragma once
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/pipeline.h"

namespace tandem {

using PipelineEdit = std::function<void(Pipeline&)>;
using PipelineEdits = std::vector<PipelineEdit>;

// Edits every pass of type P named `name`; a pipeline without one is a logic_error (the caller
// chose the pipeline).
template <class P, class Fn>
PipelineEdit editPass(std::string name, Fn fn) {
  return [name = std::move(name), fn](Pipeline& pipeline) {
    bool found = false;
    for (auto& pass : pipeline.passes) {
      if (pass->name() != name) continue;
      P* typed = dynamic_cast<P*>(pass.get());
      if (!typed)
        throw std::logic_error("pass '" + name + "' of pipeline '" + pipeline.name +
                               "' is not of the type the edit expects");
      typename P::Settings s = typed->settings();
      fn(s);
      typed->assign(s);
      found = true;
    }
    if (!found)
      throw std::logic_error("pipeline '" + pipeline.name + "' has no pass '" + name + "'");
  };
}

// The same for the passes of type P that carry no label (named by their type).
template <class P, class Fn>
PipelineEdit editPass(Fn fn) {
  return editPass<P>(P().type(), std::move(fn));
}

inline void applyEdits(Pipeline& p, const PipelineEdits& edits) {
  for (const PipelineEdit& e : edits) e(p);
}

}  // namespace tandem
