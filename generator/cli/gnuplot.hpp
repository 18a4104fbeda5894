#pragma once
// Plots drawn by gnuplot from a script we write: the plot file appears whole or not at all.
#include <functional>
#include <string>

namespace eomgen::tools {

/// A title or a label as a string in gnuplot's single quotes, where only the quote itself is
/// special ('' in it): line breaks, which would end the command, are left out, and bytes that
/// are not UTF-8 (a model named after such a file) become U+FFFD, so an SVG stays valid XML.
std::string gnuplot_text(const std::string& text);

/// A file's path as a string in gnuplot's single quotes, byte for byte: they carry every byte
/// but a line break.
/// \throws eomgen::Error for a line break (require_gnuplot_path refuses such paths first)
std::string gnuplot_path(const std::string& path);

/// \throws UsageError naming `option` if `path`, made absolute as gnuplot gets it (also with
/// symbolic links followed, as a plot is written), holds a line break (LF or CR), which ends a
/// gnuplot command whatever the quoting
void require_gnuplot_path(const std::string& path, const std::string& option);

/// \throws UsageError unless `plot_path` ends in .svg or .png and gnuplot can take it
/// (require_gnuplot_path; `option` names the flag)
/// \throws eomgen::Error if gnuplot is not installed (`alternative`: what to pass instead)
void require_plot_target(const std::string& plot_path, const std::string& option, const std::string& alternative);

/// gnuplot's terminal line for the plot's type (.png: pngcairo, else svg), `width` x `height`
std::string gnuplot_terminal(const std::string& plot_path, int width, int height);

/// The exit status of a run whose data was written in full but whose plot was not.
inline constexpr int plot_failed_status = 3;

/// Says on stderr that the plot `plot_path` was not written and why (`failure`), and that
/// `kept` ("the CSV 'run.csv'") is complete and stays. \return plot_failed_status
int report_plot_failure(const std::string& plot_path, const std::string& kept, const std::exception& failure);

/// Runs gnuplot on `script(image)`, where image is the absolute path gnuplot must write (a
/// temporary file renamed to `plot_path` once gnuplot succeeds).
/// \throws eomgen::Error with gnuplot's output if it fails or writes nothing; nothing is written
/// then
void plot_with_gnuplot(const std::string& plot_path, const std::function<std::string(const std::string& image)>& script);

}  // namespace eomgen::tools
