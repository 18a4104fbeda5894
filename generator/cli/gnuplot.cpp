#include "gnuplot.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "eomgen/base/error.hpp"
#include "file_output.hpp"
#include "interruption.hpp"
#include "process.hpp"
#include "simulate_command.hpp"

namespace eomgen::tools {

namespace fs = std::filesystem;

std::string gnuplot_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += '\'';
    if (c == '\n' || c == '\r') continue;
    out += c;
  }
  return out + "'";
}

void require_plot_target(const std::string& plot_path, const std::string& option, const std::string& alternative) {
  const std::string ext = fs::path(plot_path).extension().string();
  if (ext != ".svg" && ext != ".png")
    throw UsageError(fmt::format("{}: expected a .svg or .png file, got '{}'", option, plot_path));
  if (!program_available("gnuplot"))
    throw Error(fmt::format("gnuplot is not installed (on Debian: apt-get install gnuplot-nox); install it or {}",
                            alternative));
}

std::string gnuplot_terminal(const std::string& plot_path, int width, int height) {
  return fs::path(plot_path).extension() == ".png"
             ? fmt::format("set terminal pngcairo size {},{} noenhanced font 'sans,10'\n", width, height)
             : fmt::format("set terminal svg size {},{} dynamic noenhanced font 'sans,11' background rgb 'white'\n",
                           width, height);
}

void plot_with_gnuplot(const std::string& plot_path, const std::function<std::string(const std::string& image)>& script) {
  PendingFile image(plot_path);
  PendingFile script_file(plot_path + ".gp");
  // absolute paths: gnuplot runs a data file named "<cmd" and an output named "|cmd" as shell
  // commands, whatever the quoting; a path starting with '/' is never one
  write_atomically(script_file.path(), script(fs::absolute(image.path()).string()));
  // gnuplot's output, read and removed whatever happens (posix_spawn creates it even when
  // gnuplot cannot be started)
  struct Log {
    fs::path path;
    explicit Log(fs::path p) : path(std::move(p)) { interruption::remember(path.string()); }
    ~Log() {
      interruption::Hold hold;
      std::error_code ec;
      fs::remove(path, ec);
      interruption::forget(path.string());
    }
  } log(fs::path(script_file.path()).replace_extension(".log"));
  const int plotted = run_process({"gnuplot", fs::absolute(script_file.path()).string()}, log.path.string());
  std::ifstream in(log.path, std::ios::binary);
  std::ostringstream output;
  output << in.rdbuf();
  in.close();
  if (plotted != 0) throw Error(fmt::format("gnuplot failed (exit status {}):\n{}", plotted, output.str()));
  image.commit();
}

}  // namespace eomgen::tools
