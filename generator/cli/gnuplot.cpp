#include "gnuplot.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "eomgen/base/error.hpp"
#include "eomgen/base/utf8.hpp"
#include "file_output.hpp"
#include "interruption.hpp"
#include "process.hpp"
#include "simulate_command.hpp"

namespace eomgen::tools {

namespace fs = std::filesystem;

namespace {

std::string single_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// a path in a message, its line breaks visible
std::string shown(const std::string& path) {
  std::string out;
  for (char c : path) out += c == '\n' ? std::string("\\n") : c == '\r' ? std::string("\\r") : std::string(1, c);
  return out;
}

}  // namespace

std::string gnuplot_text(const std::string& text) {
  std::string clean;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence_length(text, i);
    if (n == 0) {
      clean += "\xEF\xBF\xBD";  // U+FFFD for the byte that starts no character
      ++i;
      continue;
    }
    if (text[i] != '\n' && text[i] != '\r') clean += text.substr(i, n);
    i += n;
  }
  return single_quoted(clean);
}

std::string gnuplot_path(const std::string& path) {
  if (path.find_first_of("\n\r") != std::string::npos)
    throw Error(fmt::format("gnuplot cannot take the path '{}': it has a line break", shown(path)));
  return single_quoted(path);
}

void require_gnuplot_path(const std::string& path, const std::string& option) {
  // gnuplot gets the path made absolute, and writes next to the file a symbolic link names
  for (const std::string& seen : {fs::absolute(path).string(), written_file(path)}) {
    if (seen.find_first_of("\n\r") == std::string::npos) continue;
    throw UsageError(fmt::format("{}: '{}'{} has a line break, which ends a command of gnuplot whatever the quoting; "
                                 "choose a path without one",
                                 option, shown(path),
                                 seen == path ? std::string() : fmt::format(" (as gnuplot gets it: '{}')", shown(seen))));
  }
}

void require_plot_target(const std::string& plot_path, const std::string& option, const std::string& alternative) {
  const std::string ext = fs::path(plot_path).extension().string();
  if (ext != ".svg" && ext != ".png")
    throw UsageError(fmt::format("{}: expected a .svg or .png file, got '{}'", option, shown(plot_path)));
  require_gnuplot_path(plot_path, option);
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

int report_plot_failure(const std::string& plot_path, const std::string& kept, const std::exception& failure) {
  std::cerr << fmt::format("eomgen: error: the plot '{}' was not written ({} is complete and kept): {}\n", plot_path,
                           kept, failure.what());
  return plot_failed_status;
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
  std::error_code ec;
  if (fs::file_size(image.path(), ec) == 0 || ec)
    throw Error(fmt::format("gnuplot ended with status 0 but wrote no image:\n{}", output.str()));
  image.commit();
}

}  // namespace eomgen::tools
