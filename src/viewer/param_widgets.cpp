#include "viewer/param_widgets.h"

#include <cstdio>

namespace tandem {

namespace {
std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}
}  // namespace

ParamWidget paramWidget(const ParamDesc& d) {
  ParamWidget w;
  w.param = w.label = d.name;
  w.min = d.min;
  w.max = d.max;
  w.defaultValue = d.defaultValue;
  w.choices = d.choices;
  switch (d.type) {
    case ParamType::Bool:
      w.kind = WidgetKind::Checkbox;
      break;
    case ParamType::Enum:
      w.kind = WidgetKind::Combo;
      break;
    case ParamType::Int:
      w.kind = d.max - d.min <= 1000 ? WidgetKind::SliderInt : WidgetKind::DragInt;
      break;
    case ParamType::Float:
      // Decades of range read best on a log scale; a bounded span on a plain slider; anything
      // wider as a drag field.
      if (d.min > 0 && d.max / d.min >= 1000)
        w.kind = WidgetKind::SliderFloatLog;
      else if (d.max - d.min <= 1e4)
        w.kind = WidgetKind::SliderFloat;
      else
        w.kind = WidgetKind::DragFloat;
      break;
  }
  w.tooltip = d.doc;
  if (d.type == ParamType::Enum) {
    w.tooltip += " (";
    for (size_t i = 0; i < d.choices.size(); ++i) w.tooltip += (i ? ", " : "") + d.choices[i];
    w.tooltip += "; default " + d.choices.at(size_t(d.defaultValue)) + ")";
  } else if (d.type == ParamType::Bool) {
    w.tooltip += std::string(" (default ") + (d.defaultValue != 0 ? "on" : "off") + ")";
  } else {
    w.tooltip +=
        " [" + number(d.min) + ", " + number(d.max) + "], default " + number(d.defaultValue);
  }
  return w;
}

std::vector<ParamWidget> paramWidgets(const Pass& pass) {
  std::vector<ParamWidget> out;
  for (const ParamDesc& d : pass.params()) out.push_back(paramWidget(d));
  return out;
}

}  // namespace tandem
