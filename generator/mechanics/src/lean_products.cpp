#include "eomgen/mechanics/lean_products.hpp"

#include <algorithm>

#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/simplify.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

std::vector<FrameId> frames_of(const Vector& u, const Vector& v) {
  std::vector<FrameId> frames;
  for (const Vector* w : {&u, &v})
    for (const auto& [frame, c] : w->terms()) frames.push_back(frame);
  return frames;
}

std::size_t vector_size(const Vector& v) {
  std::size_t size = 0;
  for (const auto& [frame, c] : v.terms())
    for (unsigned i = 0; i < 3; ++i) size += expression_size(c(i, 0));
  return size;
}

// the smallest of `fallback` and, for each candidate frame f, the simplified column(f) as a
// vector in f; ties keep the earlier, so the result does not depend on GiNaC's term order
template <class Column>
Vector smallest_vector(const std::vector<FrameId>& candidates, Vector fallback, Column&& column) {
  Vector best = std::move(fallback);
  std::size_t best_size = vector_size(best);
  for (const FrameId f : candidates) {
    const Vector here(f, simplify_for_display(column(f)));
    const std::size_t size = vector_size(here);
    if (size < best_size) {
      best = here;
      best_size = size;
    }
  }
  return best;
}

}  // namespace

std::size_t expression_size(const GiNaC::ex& e) {
  return static_cast<std::size_t>(std::distance(e.preorder_begin(), e.preorder_end()));
}

std::vector<FrameId> frames_between(const MechanicalSystem& s, const std::vector<FrameId>& frames) {
  if (frames.empty()) return {};
  FrameId ancestor = frames.front();
  for (const FrameId f : frames) ancestor = common_ancestor(s, ancestor, f);
  std::vector<FrameId> out;
  auto add = [&](FrameId f) {
    if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  };
  for (FrameId f : frames) {
    for (; f != ancestor; f = *s.frame(f).parent) add(f);
  }
  add(ancestor);
  return out;
}

ex lean_dot(const MechanicalSystem& s, const Vector& u, const Vector& v) {
  ex best = dot(s, u, v);
  std::size_t best_size = expression_size(best);
  for (const FrameId f : frames_between(s, frames_of(u, v))) {
    const matrix uf = resolve(s, u, f), vf = resolve(s, v, f);
    const ex here = simplify_for_display(uf(0, 0) * vf(0, 0) + uf(1, 0) * vf(1, 0) + uf(2, 0) * vf(2, 0));
    const std::size_t size = expression_size(here);
    if (size < best_size) {
      best = here;
      best_size = size;
    }
  }
  return best;
}

ex lean_norm(const MechanicalSystem& s, const Vector& v) { return GiNaC::sqrt(lean_dot(s, v, v)); }

Vector lean_cross(const MechanicalSystem& s, const Vector& u, const Vector& v) {
  return smallest_vector(frames_between(s, frames_of(u, v)), cross(s, u, v),
                         [&](FrameId f) { return cross_matrix(resolve(s, u, f)).mul(resolve(s, v, f)); });
}

Vector lean_resolved(const MechanicalSystem& s, const Vector& v) {
  return smallest_vector(frames_between(s, frames_of(v, Vector())), v, [&](FrameId f) { return resolve(s, v, f); });
}

}  // namespace eomgen
