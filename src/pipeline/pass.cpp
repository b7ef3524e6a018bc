#include "pipeline/pass.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace tandem {

double Pass::param(const std::string& name) const {
  auto it = values_.find(name);
  if (it != values_.end()) return it->second;
  for (const ParamDesc& d : params())
    if (d.name == name) return d.defaultValue;
  TANDEM_ASSERT(!"pass reads a parameter it does not declare");
  return 0;
}

void Pass::setParam(const std::string& name, double value) {
  for (const ParamDesc& d : params()) {
    if (d.name != name) continue;
    if (!std::isfinite(value) || value < d.min || value > d.max) {
      std::ostringstream os;
      os << "value " << value << " out of range [" << d.min << ", " << d.max << "]";
      throw InputError("", "pass '" + type() + "' parameter '" + name + "'", os.str());
    }
    if ((d.type == ParamType::Int || d.type == ParamType::Enum || d.type == ParamType::Bool) &&
        value != std::floor(value))
      throw InputError("", "pass '" + type() + "' parameter '" + name + "'", "expected an integer");
    if (d.invalidatesHistory && param(name) != value) historyInvalidated = true;
    values_[name] = value;
    onParamSet(name, value);
    return;
  }
  throw InputError("", "pass '" + type() + "' parameter '" + name + "'", "unknown parameter");
}

void Pass::resetParams() {
  values_.clear();
  onParamsReset();
}

const std::string& Pass::bufferName(const std::string& slot) const {
  auto it = bindings.find(slot);
  return it != bindings.end() ? it->second : slot;
}

namespace {
std::optional<BufferSlot> findSlot(const std::vector<BufferSlot>& slots, const std::string& name) {
  for (const BufferSlot& s : slots)
    if (s.slot == name) return s;
  return std::nullopt;
}
}  // namespace

std::optional<BufferSlot> Pass::outputSlot(const std::string& slot) const {
  return findSlot(outputs(), slot);
}

std::optional<BufferSlot> Pass::inputSlot(const std::string& slot) const {
  return findSlot(inputs(), slot);
}

bool Pass::declaresCounter(const std::string& name) const {
  for (const CounterDesc& c : counters())
    if (c.name == name) return true;
  return false;
}

}  // namespace tandem
