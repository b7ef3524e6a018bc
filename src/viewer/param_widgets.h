// The viewer's parameter panel is generated, not written per pass: each ParamDesc (type, range,
// default, doc) maps to one widget description, which the ImGui front end draws. Kept free of
// any UI library so the mapping is tested for every parameter of every pass.
#pragma once
#include <string>
#include <vector>

#include "pipeline/pass.h"

namespace tandem {

enum class WidgetKind {
  Checkbox,        // Bool
  Combo,           // Enum: one of `choices`
  SliderInt,       // Int with a small range
  DragInt,         // Int with a wide range (clamped to [min, max])
  SliderFloat,     // Float with a moderate range
  SliderFloatLog,  // Float spanning decades (min > 0): logarithmic slider
  DragFloat,       // Float with a huge range (clamped to [min, max])
};

struct ParamWidget {
  std::string param;    // parameter name, as in "label.param"
  std::string label;    // shown next to the widget
  std::string tooltip;  // the parameter's doc, range and default
  WidgetKind kind = WidgetKind::SliderFloat;
  double min = 0, max = 1, defaultValue = 0;
  std::vector<std::string> choices;
};

ParamWidget paramWidget(const ParamDesc& d);
std::vector<ParamWidget> paramWidgets(const Pass& pass);

}  // namespace tandem
