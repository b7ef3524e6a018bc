// tandem pipeline NAME|FILE: what a pipeline is made of — its passes in order, the buffers each
// reads and writes with their channels, kinds and extents, and the history kept between frames;
// --dot FILE also writes it as a Graphviz graph (dot -Tpng FILE -o pipeline.png).
#include <cstdio>

#include "cli_options.h"
#include "core/error.h"
#include "core/image_io.h"
#include "pipeline/pipeline_graph.h"
#include "verbs.h"

namespace tandem {

VerbRunner addPipelineVerb(CLI::App& app) {
  struct Args {
    std::string name, dot;
    std::vector<std::string> sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "pipeline", "Show a pipeline's passes, buffers (kinds, extents) and history edges");
  sub->add_option("name", a->name, "Built-in pipeline name or pipeline JSON file")->required();
  sub->add_option("--set", a->sets, "Set a pass parameter first (pass.param=value)");
  sub->add_option("--dot", a->dot, "Also write the pipeline as a Graphviz graph (.dot)");
  return [a] {
    if (!a->dot.empty() && !hasExtension(a->dot, ".dot") && !hasExtension(a->dot, ".gv"))
      throw InputError("command line", "--dot", "must name a .dot or .gv file");
    Pipeline p = Pipeline::load(a->name);
    for (const std::string& s : a->sets) p.setParam(s, "--set");
    p.checkShadows("--set");
    std::fputs(describePipeline(p).c_str(), stdout);
    if (!a->dot.empty()) {
      writeTextFile(a->dot, pipelineDot(p));
      std::printf("wrote %s\n", a->dot.c_str());
    }
    return 0;
  };
}

}  // namespace tandem
