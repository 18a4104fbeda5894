#pragma once
// Physical vectors in vectrix form: a sum of terms F_f^T v_f, each term a column of
// components resolved in one frame. Terms stay in the frame they were given in until an
// operation needs a common frame; this keeps expressions short and local.
#include <ginac/ginac.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace eomgen {

/// Index of a frame in its MechanicalSystem.
struct FrameId {
  std::size_t index = 0;
  friend bool operator==(FrameId a, FrameId b) { return a.index == b.index; }
  friend bool operator!=(FrameId a, FrameId b) { return a.index != b.index; }
  friend bool operator<(FrameId a, FrameId b) { return a.index < b.index; }
};

/// Index of a point in its MechanicalSystem.
struct PointId {
  std::size_t index = 0;
  friend bool operator==(PointId a, PointId b) { return a.index == b.index; }
  friend bool operator!=(PointId a, PointId b) { return a.index != b.index; }
};

class Vector {
 public:
  using Term = std::pair<FrameId, GiNaC::matrix>;

  /// The zero vector.
  Vector() = default;
  /// F_frame^T components (components: 3x1). \throws ModelError for another shape.
  Vector(FrameId frame, const GiNaC::matrix& components);
  Vector(FrameId frame, const GiNaC::ex& x, const GiNaC::ex& y, const GiNaC::ex& z);

  /// Terms sorted by frame index, one per frame; zero terms removed.
  const std::vector<Term>& terms() const { return terms_; }
  bool is_zero() const { return terms_.empty(); }

  Vector operator+(const Vector& other) const;
  Vector operator-(const Vector& other) const;
  Vector operator-() const;
  Vector& operator+=(const Vector& other);
  /// Scalar product.
  friend Vector operator*(const GiNaC::ex& s, const Vector& v);
  friend Vector operator*(const Vector& v, const GiNaC::ex& s) { return s * v; }

  /// Applies f to every component (for subs, diff, expand, evalf...).
  template <class F>
  Vector map_components(F&& f) const {
    Vector out;
    for (const auto& [frame, c] : terms_) {
      GiNaC::matrix m(3, 1);
      for (unsigned i = 0; i < 3; ++i) m(i, 0) = f(c(i, 0));
      out.add_term(frame, m);
    }
    return out;
  }

 private:
  void add_term(FrameId frame, const GiNaC::matrix& components);
  std::vector<Term> terms_;
};

}  // namespace eomgen
