// A pipeline shown as what it is: its passes in order with the buffers each reads and writes
// (channels, kind, extent; history and optional inputs marked), and the same as a Graphviz graph
// (passes as boxes, buffers as ellipses, history edges dashed), as Filament's FrameGraph exports
// one. `tandem pipeline NAME [--dot FILE]` prints and writes them.
#pragma once
#include <string>

#include "pipeline/pipeline.h"

namespace tandem {

std::string describePipeline(const Pipeline& p);
std::string pipelineDot(const Pipeline& p);

}  // namespace tandem
