#pragma once
// Plots drawn by gnuplot from a script we write: the plot file appears whole or not at all.
#include <functional>
#include <string>

namespace eomgen::tools {

/// A string for gnuplot's single quotes, where only the quote itself is special ('' in it);
/// line breaks, which would end the command, are left out.
std::string gnuplot_quoted(const std::string& text);

/// \throws UsageError unless `plot_path` ends in .svg or .png (`option` names the flag)
/// \throws eomgen::Error if gnuplot is not installed (`alternative`: what to pass instead)
void require_plot_target(const std::string& plot_path, const std::string& option, const std::string& alternative);

/// gnuplot's terminal line for the plot's type (.png: pngcairo, else svg), `width` x `height`
std::string gnuplot_terminal(const std::string& plot_path, int width, int height);

/// Runs gnuplot on `script(image)`, where image is the absolute path gnuplot must write (a
/// temporary file renamed to `plot_path` once gnuplot succeeds).
/// \throws eomgen::Error with gnuplot's output if it fails; nothing is written then
void plot_with_gnuplot(const std::string& plot_path, const std::function<std::string(const std::string& image)>& script);

}  // namespace eomgen::tools
