// tandem: the hybrid renderer's command line. Verbs: render, reference, info, compare, bench,
// experiment, export, view.
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <new>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/memory.h"
#include "gpu/gpu_device.h"
#include "verbs.h"

namespace {

// Ctrl-C: the render, reference or experiment stops before its next frame or sample batch and
// cleans up (an experiment's staging folder, a file being written); a second Ctrl-C ends the
// process at once.
volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) {
  gInterrupted = 1;
  std::signal(SIGINT, SIG_DFL);
}
struct Interrupted {};

}  // namespace

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
  // The viewer renders on a worker thread and quits on its own keys: Ctrl-C ends it as before.
  if (!app.got_subcommand("view")) std::signal(SIGINT, onInterrupt);
  const tandem::InterruptPoll ctrlC([] {
    if (gInterrupted) throw Interrupted{};
  });
  try {
    for (auto& [name, run] : verbs)
      if (app.got_subcommand(name)) return run();
  } catch (const Interrupted&) {
    std::fprintf(stderr, "tandem: interrupted\n");
    return 130;
  } catch (const tandem::InputError& e) {
    std::fprintf(stderr, "tandem: error: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // Where an output cannot go (a read-only or missing place, a name too long): the
    // environment's error, in Tandem's words.
    std::fprintf(stderr, "tandem: error: %s: %s\n", e.path1().string().c_str(),
                 e.code().message().c_str());
    return 2;
  } catch (const std::bad_alloc&) {
    // What the size check could not foresee (checkSceneFits is an estimate): the environment's
    // limit, in Tandem's words.
    std::fprintf(stderr,
                 "tandem: error: out of memory: this machine cannot hold what the scene and frame "
                 "need (a smaller --width / --height or scene renders)\n");
    return 2;
  } catch (const tandem::GpuError& e) {
    // The device's limits or failures (out of device memory, a lost device): the environment's.
    std::fprintf(stderr, "tandem: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tandem: error: %s\n", e.what());
    return 1;
  }
  return 1;
}
