#include "eomgen/mechanics/vector.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {
bool all_zero(const GiNaC::matrix& m) {
  for (unsigned i = 0; i < m.rows(); ++i)
    if (!m(i, 0).is_zero()) return false;
  return true;
}
}  // namespace

Vector::Vector(FrameId frame, const GiNaC::matrix& components) {
  if (components.rows() != 3 || components.cols() != 1)
    throw ModelError(fmt::format("physical vector: expected 3x1 components, got {}x{}",
                                 components.rows(), components.cols()));
  add_term(frame, components);
}

Vector::Vector(FrameId frame, const GiNaC::ex& x, const GiNaC::ex& y, const GiNaC::ex& z)
    : Vector(frame, GiNaC::matrix(3, 1, GiNaC::lst{x, y, z})) {}

void Vector::add_term(FrameId frame, const GiNaC::matrix& components) {
  auto it = std::lower_bound(terms_.begin(), terms_.end(), frame,
                             [](const Term& t, FrameId f) { return t.first < f; });
  if (it != terms_.end() && it->first == frame) {
    it->second = it->second.add(components);
    if (all_zero(it->second)) terms_.erase(it);
  } else if (!all_zero(components)) {
    terms_.insert(it, Term{frame, components});
  }
}

Vector& Vector::operator+=(const Vector& other) {
  for (const auto& [frame, c] : other.terms_) add_term(frame, c);
  return *this;
}

Vector Vector::operator+(const Vector& other) const {
  Vector out = *this;
  out += other;
  return out;
}

Vector Vector::operator-() const { return GiNaC::ex(-1) * *this; }

Vector Vector::operator-(const Vector& other) const { return *this + (-other); }

Vector operator*(const GiNaC::ex& s, const Vector& v) {
  return v.map_components([&](const GiNaC::ex& c) { return s * c; });
}

}  // namespace eomgen
