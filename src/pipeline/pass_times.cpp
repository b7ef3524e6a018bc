#include "pipeline/pass_times.h"

#include <stdexcept>
#include <utility>

namespace tandem {

PassTimes::PassTimes(const Pipeline& pipeline, std::map<std::string, double> msByRow)
    : pipeline_(pipeline), ms_(std::move(msByRow)) {}

PassTimes::PassTimes(const Pipeline& pipeline, const FrameTimings& frame) : pipeline_(pipeline) {
  for (const PassTiming& t : frame.passes) {
    ms_[t.name] += t.ms;
    rays_[t.name] += t.rays;
  }
}

bool PassTimes::has(const std::string& type) const {
  for (const auto& p : pipeline_.passes)
    if (p->type() == type) return true;
  return false;
}

double PassTimes::ofPass(size_t index) const {
  auto it = ms_.find(pipeline_.passes.at(index)->name());
  return it == ms_.end() ? 0.0 : it->second;
}

double PassTimes::ofType(const std::string& type) const {
  if (!has(type))
    throw std::logic_error("pipeline '" + pipeline_.name + "' has no pass of type '" + type + "'");
  double ms = 0;
  for (size_t i = 0; i < pipeline_.passes.size(); ++i)
    if (pipeline_.passes[i]->type() == type) ms += ofPass(i);
  return ms;
}

double PassTimes::raysOf(const std::string& type) const {
  double rays = 0;
  for (const auto& p : pipeline_.passes) {
    if (p->type() != type) continue;
    auto it = rays_.find(p->name());
    if (it != rays_.end()) rays += it->second;
  }
  return rays;
}

double PassTimes::partOf(const std::string& type, const std::string& part) const {
  double ms = 0;
  for (const auto& p : pipeline_.passes) {
    if (p->type() != type) continue;
    auto it = ms_.find(p->name() + "/" + part);
    if (it != ms_.end()) ms += it->second;
  }
  return ms;
}

std::map<std::string, double> PassTimes::byType() const {
  std::map<std::string, std::string> typeOf;  // row label -> pass type
  for (const auto& p : pipeline_.passes) typeOf[p->name()] = p->type();
  std::map<std::string, double> out;
  for (const auto& [row, ms] : ms_) {
    const size_t slash = row.find('/');
    auto it = typeOf.find(row.substr(0, slash));
    const std::string name =
        it == typeOf.end() ? row
                           : it->second + (slash == std::string::npos ? "" : row.substr(slash));
    out[name] += ms;
  }
  return out;
}

}  // namespace tandem
