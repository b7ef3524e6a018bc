// The `tandem` verbs. Each registers its sub-command and returns the exit code when run.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace tandem {

using VerbRunner = std::function<int()>;
VerbRunner addRenderVerb(CLI::App& app);
VerbRunner addInfoVerb(CLI::App& app);
VerbRunner addCompareVerb(CLI::App& app);
VerbRunner addBenchVerb(CLI::App& app);
VerbRunner addExperimentVerb(CLI::App& app);
VerbRunner addReferenceVerb(CLI::App& app);
VerbRunner addExportVerb(CLI::App& app);
VerbRunner addViewVerb(CLI::App& app);
VerbRunner addPipelineVerb(CLI::App& app);
VerbRunner addPassesVerb(CLI::App& app);

}  // namespace tandem
