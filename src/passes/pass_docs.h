// docs/passes.md, generated: every pass type by technique (its description, the buffers it reads
// and writes, its parameters with type, default, range and description) and every built-in
// pipeline's passes. `tandem passes` prints it; a test checks the file equals it.
#pragma once
#include <string>

namespace tandem {

std::string passesMarkdown();

}  // namespace tandem
