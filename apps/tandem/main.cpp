// tandem: the hybrid renderer's command line. Verbs: render, reference, info, compare, bench,
// experiment, export, view.
#include <csignal>
#include <cstdio>
#include <map>

#include "core/error.h"
#include "core/memory.h"
#include "verbs.h"

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) should fail the write, which FileCommit reports and cleans
  // up, rather than kill the process with a half-written temporary left behind.
  std::signal(SIGXFSZ, SIG_IGN);
  tandem::keepFreedMemoryForReuse();
  CLI::App app{"Tandem: a hybrid rasterization + ray tracing renderer"};
  app.require_subcommand(1);
  std::map<std::string, tandem::VerbRunner> verbs = {
      {"render", tandem::addRenderVerb(app)},         {"info", tandem::addInfoVerb(app)},
      {"compare", tandem::addCompareVerb(app)},       {"bench", tandem::addBenchVerb(app)},
      {"experiment", tandem::addExperimentVerb(app)}, {"reference", tandem::addReferenceVerb(app)},
      {"export", tandem::addExportVerb(app)},         {"view", tandem::addViewVerb(app)},
      {"pipeline", tandem::addPipelineVerb(app)},     {"passes", tandem::addPassesVerb(app)}};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and friends: CLI11 prints them and exits 0. Every other parse error is bad input:
    // exit 2 with Tandem's wording, like every other error.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "tandem: error: command line: %s (see tandem --help)\n", e.what());
    return 2;
  }
  try {
    for (auto& [name, run] : verbs)
      if (app.got_subcommand(name)) return run();
  } catch (const tandem::InputError& e) {
    std::fprintf(stderr, "tandem: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tandem: error: %s\n", e.what());
    return 1;
  }
  return 1;
}
