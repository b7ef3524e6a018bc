// Typed pass settings: a pass keeps its parameters in a struct S whose members carry the
// defaults, and binds each member once to its ParamDesc. The pass then reads `settings().member`
// (no string lookup per frame; a misspelt member does not compile), while the pipeline, `--set`,
// the viewer and docs/passes.md still see the ParamDesc list. Settings several passes share (the
// Whitted parameters) are a struct of their own with its own table, nested into each pass's.
#pragma once
#include <charconv>
#include <cstdlib>
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
    if (d.type == ParamType::Enum) {
      d.min = 0;
      d.max = double(d.choices.size()) - 1;
    } else if (d.type == ParamType::Bool) {
      d.min = 0;
      d.max = 1;
    }
    Binding b{[member](S& s, double v) {
                if constexpr (std::is_enum_v<T>)
                  s.*member = T(int(v));
                else if constexpr (std::is_same_v<T, bool>)
                  s.*member = v != 0;
                else
                  s.*member = T(v);
              },
              [member](const S& s) {
                if constexpr (std::is_enum_v<T>)
                  return double(int(s.*member));
                else if constexpr (std::is_same_v<T, float>)
                  return shortestDouble(s.*member);
                else
                  return double(s.*member);
              }};
    d.defaultValue = b.get(S{});
    descs_.push_back(std::move(d));
    bindings_.push_back(std::move(b));
    return *this;
  }
  // Binds every parameter of a nested settings struct under its own names; the defaults are
  // those of `member`'s initialiser here (a pass may default a shared setting differently).
  template <class N>
  ParamTable& nest(N S::*member, const ParamTable<N>& inner) {
    const S defaults{};
    for (size_t i = 0; i < inner.descs_.size(); ++i) {
      ParamDesc d = inner.descs_[i];
      const auto& in = inner.bindings_[i];
      d.defaultValue = in.get(defaults.*member);
      descs_.push_back(std::move(d));
      bindings_.push_back({[member, set = in.set](S& s, double v) { set(s.*member, v); },
                           [member, get = in.get](const S& s) { return get(s.*member); }});
    }
    return *this;
  }

  const std::vector<ParamDesc>& descs() const { return descs_; }
  // Parameter i's value in s (the index into descs()).
  double value(const S& s, size_t i) const { return bindings_[i].get(s); }
  // Writes parameter `name` (already validated by Pass::setParam) into s.
  void assign(S& s, const std::string& name, double value) const {
    for (size_t i = 0; i < descs_.size(); ++i)
      if (descs_[i].name == name) bindings_[i].set(s, value);
  }

 private:
  template <class>
  friend class ParamTable;
  // A float member's value as the double its shortest decimal reads as (0.01f shows and compares
  // as 0.01, and converts back to the same float).
  static double shortestDouble(float f) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof(text) - 1, f).ptr;
    *end = '\0';
    return std::strtod(text, nullptr);
  }
  struct Binding {
    std::function<void(S&, double)> set;
    std::function<double(const S&)> get;
  };
  std::vector<ParamDesc> descs_;
  std::vector<Binding> bindings_;
};

// A pass whose parameters are the settings struct S, bound by the static table `tableFor()`.
template <class S>
class SettingsPass : public Pass {
 public:
  using Settings = S;
  std::vector<ParamDesc> params() const override { return tableFor().descs(); }
  const S& settings() const { return settings_; }
  // Every parameter from `s`, each checked as setParam checks it (range, choices), so what the
  // viewer, the docs and --set read follows.
  void assign(const S& s) {
    const ParamTable<S>& t = tableFor();
    for (size_t i = 0; i < t.descs().size(); ++i) setParam(t.descs()[i].name, t.value(s, i));
  }

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
