// Procedural scenes that need no files: `cornell`, `spheres`, `atrium`.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace tandem {

const std::vector<std::string>& builtinSceneNames();
bool isBuiltinScene(const std::string& name);
Scene makeBuiltinScene(const std::string& name);  // throws InputError for an unknown name

Scene makeCornellScene();
Scene makeSpheresScene();
Scene makeAtriumScene();

}  // namespace tandem
