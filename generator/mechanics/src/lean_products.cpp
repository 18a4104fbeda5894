#include "eomgen/mechanics/lean_products.hpp"

#include <algorithm>

#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/expression_size.hpp"
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

// Simplifying multiplies out: an expression that would multiply out to more nodes than this
// (a point defined from other points' positions inside functions, a graph of a few nodes per
// point and an exponentially large tree) is kept as it is rather than simplified in any frame.
// Every product of the shipped models multiplies out to a few hundred nodes.
constexpr double largest_simplified = 20000;

bool simplifiable(const ex& e) { return ExpressionSizes().expanded(e).nodes <= largest_simplified; }

bool simplifiable(const matrix& m) {
  ExpressionSizes sizes;
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      if (sizes.expanded(m(i, j)).nodes > largest_simplified) return false;
  return true;
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
    const matrix components = column(f);
    if (!simplifiable(components)) continue;
    const Vector here(f, simplify_for_display(components));
    const std::size_t size = vector_size(here);
    if (size < best_size) {
      best = here;
      best_size = size;
    }
  }
  return best;
}

}  // namespace

std::size_t expression_size(const GiNaC::ex& e) { return static_cast<std::size_t>(tree_size(e)); }

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
    const ex product = uf(0, 0) * vf(0, 0) + uf(1, 0) * vf(1, 0) + uf(2, 0) * vf(2, 0);
    if (!simplifiable(product)) continue;
    const ex here = simplify_for_display(product);
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
