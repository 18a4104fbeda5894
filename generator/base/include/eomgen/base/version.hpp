#pragma once
namespace eomgen {
/// Stamped into generated code and printed by `eomgen --version`.
inline constexpr const char* version = "0.1.0";
}  // namespace eomgen
