#pragma once
// Include before anything that includes Eigen. Eigen checks its no-malloc flag with
// eigen_assert, which NDEBUG compiles out; counting failed assertions instead keeps the
// allocation tests meaningful in every build type:
//   eigen_assert_failures = 0;
//   Eigen::internal::set_is_malloc_allowed(false);
//   ... code that must not allocate ...
//   Eigen::internal::set_is_malloc_allowed(true);
//   EXPECT_EQ(eigen_assert_failures, 0);
#ifdef EIGEN_WORLD_VERSION
#error "runtime/no_malloc.hpp must be included before any Eigen header"
#endif

namespace {
int eigen_assert_failures = 0;
}  // namespace
#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(x) ((x) ? void(0) : void(++eigen_assert_failures))
