#pragma once
// Sines and cosines of sums of angles from those of their parts, by the addition theorems
//   sin(a + b) = sin a cos b + cos a sin b,   cos(a + b) = cos a cos b - sin a sin b,
// where the parts' sines or cosines are computed anyway.
//
// A chain's relative joint angles make sin(q1 + q2) beside sin(q1) and sin(q2). A call to sin
// costs as much as a dozen multiplications, while the partner of a computed sine or cosine is
// nearly free: the compiler merges sin(x) and cos(x) of one argument into one call of sincos
// (GCC and Clang do at -O1 and above, without -ffast-math). So a sum whose parts' sines or
// cosines are in the program anyway is computed in three operations per function instead of
// a call. Parts are the terms of the sum, or smaller sums that the program takes the sine or
// cosine of.
#include "eomgen/codegen/ir.hpp"

namespace eomgen {

/// The program with sin(s) and cos(s) of every sum s that splits into parts whose sines or
/// cosines the program computes anyway rewritten by the addition theorems, and the values no
/// output needs any more dropped. A program without such sums comes back as it was.
/// Deterministic: decisions follow instruction order and content only.
ir::Program expand_angle_sums(const ir::Program& program);

}  // namespace eomgen
