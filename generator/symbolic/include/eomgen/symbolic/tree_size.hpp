#pragma once
// The size of an expression as a tree: what printing it, or differentiating it without
// intermediates, costs. GiNaC shares equal subtrees in memory, so an expression of modest
// memory can be an exponentially large tree.
#include <ginac/ginac.h>

namespace eomgen {

/// Number of nodes of e written out as a tree (intermediates count as leaves), computed
/// visiting each shared node once.
double tree_size(const GiNaC::ex& e);

}  // namespace eomgen
