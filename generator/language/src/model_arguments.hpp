#pragma once
// The key = value arguments of an element statement, checked against what the statement takes.
// Shared by the statements of model_elements.cpp and model_wheel.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "eomgen/base/error.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {

class Elaborator::Arguments {
 public:
  Arguments(Elaborator& elaborator, const Instance& in, std::string what, std::vector<std::string> allowed)
      : elaborator_(elaborator), s_(*in.statement), env_(in.environment), what_(std::move(what)),
        allowed_(std::move(allowed)) {
    for (const Argument& a : s_.arguments) {
      if (std::find(allowed_.begin(), allowed_.end(), a.key) == allowed_.end())
        throw SourceError(a.location, fmt::format("{}: unknown argument '{}'; expected {}", what_, a.key, list()));
      for (const Argument& b : s_.arguments)
        if (&b != &a && b.key == a.key && &b > &a)
          throw SourceError(b.location, fmt::format("{}: argument '{}' is given twice", what_, a.key));
    }
  }
  const Argument* find(const std::string& key) const {
    for (const Argument& a : s_.arguments)
      if (a.key == key) return &a;
    return nullptr;
  }
  const Argument& require(const std::string& key, const std::string& hint) const {
    if (const Argument* a = find(key)) return *a;
    throw SourceError(s_.location, fmt::format("{}: missing argument '{}' ({})", what_, key, hint));
  }
  // `centre`, or `center` as it may also be spelled
  const Argument& centre(const std::string& hint) const {
    if (const Argument* a = find("centre")) return *a;
    if (const Argument* a = find("center")) return *a;
    return require("centre", hint);
  }
  const Name& name_of(const Argument& a, const std::string& expected) const {
    if (a.value->kind != Expr::Kind::name)
      throw SourceError(a.value->location, fmt::format("{}: argument '{}' must name {}", what_, a.key, expected));
    return a.value->name;
  }
  PointId point(const char* key) const {
    return elaborator_.point_named(name_of(require(key, "a point"), "a point"), env_);
  }
  FrameId frame(const char* key, const char* hint) const {
    return elaborator_.frame_named(name_of(require(key, hint), "a frame"), env_);
  }
  GiNaC::ex scalar(const char* key, const char* hint) const {
    return elaborator_.scalar(require(key, hint).value, env_, fmt::format("{}: '{}'", what_, key));
  }
  GiNaC::ex optional_scalar(const char* key) const {
    const Argument* a = find(key);
    return a ? elaborator_.scalar(a->value, env_, fmt::format("{}: '{}'", what_, key)) : GiNaC::ex(0);
  }
  eomgen::Vector vector(const char* key) const {
    return elaborator_.vector(require(key, "a vector").value, env_, what_);
  }
  // what the unit check asks of the argument `key`, which the statement has
  UnitChecks::Obligation expect(const char* key, const Dimension& d, const char* role,
                                const char* preferred = "") const {
    return UnitChecks::expect(d, start_of(*find(key)->value), what_, role, preferred);
  }

 private:
  std::string list() const {
    std::string out;
    for (std::size_t i = 0; i < allowed_.size(); ++i) out += (i ? ", " : "") + allowed_[i];
    return out;
  }
  Elaborator& elaborator_;
  const Statement& s_;
  const Environment& env_;
  std::string what_;
  std::vector<std::string> allowed_;
};

}  // namespace eomgen::syntax
