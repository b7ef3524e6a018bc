// The registry of pass types: what createPass() can make, and which technique folder each
// belongs to (docs/passes.md groups them so).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "pipeline/pass.h"

namespace tandem {

struct PassEntry {
  std::string type;       // the JSON pass type (the class's type())
  std::string technique;  // its folder under src/passes/
  std::unique_ptr<Pass> (*make)();
};

const std::vector<PassEntry>& passRegistry();

}  // namespace tandem
