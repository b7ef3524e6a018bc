#include "core/buffer.h"

namespace tandem {

const char* kindName(BufferKind k) {
  switch (k) {
    case BufferKind::Color:
      return "colour";
    case BufferKind::Display:
      return "display colour";
    case BufferKind::Depth:
      return "depth";
    case BufferKind::Position:
      return "position";
    case BufferKind::Normal:
      return "normal";
    case BufferKind::Id:
      return "id";
    case BufferKind::Motion:
      return "motion";
    case BufferKind::Mask:
      return "mask";
    case BufferKind::Count:
      return "count";
    case BufferKind::Signed:
      return "signed";
    case BufferKind::Variance:
      return "variance";
    case BufferKind::Material:
      return "material";
    case BufferKind::List:
      return "list";
    case BufferKind::Record:
      return "record";
  }
  return "?";
}

std::vector<std::string> channelNamesOf(const BufferSlot& s) {
  if (!s.channelNames.empty()) return s.channelNames;
  if (s.kind == BufferKind::Record) return {};
  if (s.channels == 1) return {};  // one value: the slot's name says what it is
  const bool rgb = s.kind == BufferKind::Color || s.kind == BufferKind::Display;
  if (s.channels == 3 && rgb) return {"r", "g", "b"};
  if (s.channels == 3 && (s.kind == BufferKind::Position || s.kind == BufferKind::Normal))
    return {"x", "y", "z"};
  if (s.channels == 2 && s.kind == BufferKind::Motion) return {"dx", "dy"};
  return {};
}

std::string channelList(const std::vector<std::string>& names) {
  std::string o;
  for (size_t i = 0; i < names.size(); ++i) o += (i ? ", " : "") + names[i];
  return o;
}

std::string Extent::name() const {
  switch (scale) {
    case Scale::Frame:
      return "frame";
    case Scale::Half:
      return "1/2 frame";
    case Scale::Quarter:
      return "1/4 frame";
    case Scale::Fixed:
      return std::to_string(width) + "x" + std::to_string(height);
    case Scale::Any:
      return "any size";
  }
  return "?";
}

}  // namespace tandem
