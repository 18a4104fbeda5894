#pragma once
// `eomgen linearize`: the linear model about one operating point, or a sweep of one value with
// the eigenvalues, the verdicts and where they change; as text, LaTeX, JSON or CSV.
#include "command_line.hpp"

namespace eomgen::tools {

/// \return the exit status: 0, or plot_failed_status when a sweep was written but its plot was not
/// \throws UsageError for a malformed --sweep, a format the request cannot have, or names
///   given twice; eomgen::Error for a model or a point that cannot be linearized
int run_linearize(const Options& o);

}  // namespace eomgen::tools
