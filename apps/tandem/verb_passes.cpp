// tandem passes: the reference of every pass type (buffers, parameters with type, default, range
// and description) and built-in pipeline, as Markdown: docs/passes.md is this output.
#include <cstdio>

#include "core/image_io.h"
#include "passes/pass_docs.h"
#include "verbs.h"

namespace tandem {

VerbRunner addPassesVerb(CLI::App& app) {
  auto out = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand(
      "passes", "Print the reference of every pass and built-in pipeline (docs/passes.md)");
  sub->add_option("--out", *out, "Write it to this file instead of standard output");
  return [out] {
    const std::string md = passesMarkdown();
    if (out->empty()) {
      std::fputs(md.c_str(), stdout);
    } else {
      writeTextFile(*out, md);
      std::printf("wrote %s\n", out->c_str());
    }
    return 0;
  };
}

}  // namespace tandem
