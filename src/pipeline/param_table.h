// Typed pass settings: a pass keeps its parameters in a struct S whose members carry the
// defaults, and binds each member once to its ParamDesc. The pass then reads `settings().member`
// (no string lookup per frame; a misspelt member does not compile), while the pipeline, `--set`,
// the viewer and docs/passes.md still see the ParamDesc list.
#pragma once
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pipeline/pass.h"

namespace tandem {

template <class S>
class ParamTable {
 public:
  // Binds `member` to `d`: its type follows the member's (float/double, int, bool, enum) and its
  // default is the member's initialiser.
  template <class T>
  ParamTable& add(T S::*member, ParamDesc d) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>, "parameters are numbers");
    if constexpr (std::is_enum_v<T>)
      d.type = ParamType::Enum;
    else if constexpr (std::is_same_v<T, bool>)
      d.type = ParamType::Bool;
    else if constexpr (std::is_integral_v<T>)
      d.type = ParamType::Int;
    else
      d.type = ParamType::Float;
    const S defaults{};
    if constexpr (std::is_enum_v<T>)
      d.defaultValue = double(int(defaults.*member));
    else
      d.defaultValue = double(defaults.*member);
    if (d.type == ParamType::Enum) {
      d.min = 0;
      d.max = double(d.choices.size()) - 1;
    } else if (d.type == ParamType::Bool) {
      d.min = 0;
      d.max = 1;
    }
    descs_.push_back(std::move(d));
    assign_.push_back([member](S& s, double v) {
      if constexpr (std::is_enum_v<T>)
        s.*member = T(int(v));
      else if constexpr (std::is_same_v<T, bool>)
        s.*member = v != 0;
      else
        s.*member = T(v);
    });
    return *this;
  }
  // Parameters declared elsewhere (shared by several passes) and read by their own code.
  ParamTable& append(const std::vector<ParamDesc>& more) {
    for (const ParamDesc& d : more) {
      descs_.push_back(d);
      assign_.push_back([](S&, double) {});
    }
    return *this;
  }

  const std::vector<ParamDesc>& descs() const { return descs_; }
  // Writes parameter `name` (already validated by Pass::setParam) into s.
  void assign(S& s, const std::string& name, double value) const {
    for (size_t i = 0; i < descs_.size(); ++i)
      if (descs_[i].name == name) assign_[i](s, value);
  }

 private:
  std::vector<ParamDesc> descs_;
  std::vector<std::function<void(S&, double)>> assign_;
};

// A pass whose parameters are the settings struct S, bound by the static table `table()`.
template <class S>
class SettingsPass : public Pass {
 public:
  std::vector<ParamDesc> params() const override { return tableFor().descs(); }
  const S& settings() const { return settings_; }

 protected:
  // The pass's binding, built once (a function-local static in the derived class).
  virtual const ParamTable<S>& tableFor() const = 0;
  void onParamSet(const std::string& name, double value) override {
    tableFor().assign(settings_, name, value);
  }
  void onParamsReset() override { settings_ = S{}; }

 private:
  S settings_{};
};

}  // namespace tandem
