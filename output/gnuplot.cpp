#include "output/gnuplot.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace ecorail::output {

namespace {

// Runs argv[0] (looked up on PATH) in directory cwd with standard input from /dev/null and
// standard output and error to log_path, and returns its exit status (-1: it could not be
// started or was killed). No shell is involved, so no character of an argument is special.
int run_program(const std::vector<std::string>& args, const std::filesystem::path& cwd,
                const std::filesystem::path& log_path) {
  // Everything the child needs is prepared before fork: between fork and exec only
  // async-signal-safe calls are allowed in a threaded (OpenMP) process.
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string cwd_text = cwd.string();
  const std::string log_text = log_path.string();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    // gnuplot must not outlive us (kill -9 of ecorail would leave it drawing otherwise).
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    const int in = ::open("/dev/null", O_RDONLY);
    const int log = ::open(log_text.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || log < 0 || ::chdir(cwd_text.c_str()) != 0) ::_exit(127);
    ::dup2(in, STDIN_FILENO);
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::execvp(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Directories of this kind left by a process that no longer exists (killed with SIGKILL while
// plotting: it had no chance to remove its directory) are removed by the next plot.
void remove_orphaned_temp_dirs(const std::string& stem) {
  std::error_code ec;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::temp_directory_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + stem.size(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove_all(entry.path(), ignored);
    }
  }
}

std::filesystem::path fresh_temp_dir(const char* stem) {
  remove_orphaned_temp_dirs(stem);
  static std::atomic<unsigned> counter{0};
  const auto dir =
      std::filesystem::temp_directory_path() /
      (std::string(stem) + std::to_string(::getpid()) + "-" + std::to_string(++counter));
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

std::optional<PlotFormat> plot_format_for(const std::filesystem::path& path) {
  if (path == "-") return PlotFormat::Svg;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".svg") return PlotFormat::Svg;
  if (ext == ".png") return PlotFormat::Png;
  return std::nullopt;
}

bool gnuplot_available() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const auto candidate = std::filesystem::path(dir.empty() ? "." : dir) / "gnuplot";
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) {
      return true;
    }
  }
  return false;
}

const char* gnuplot_terminal_name(PlotFormat format) {
  return format == PlotFormat::Png ? "pngcairo" : "svg";
}

bool gnuplot_supports(PlotFormat format) {
  if (!gnuplot_available()) return false;
  const auto dir = fresh_temp_dir("ecorail-gpterm-");
  const int status =
      run_program({"gnuplot", "-e", std::string("set terminal ") + gnuplot_terminal_name(format)},
                  dir, dir / "gnuplot.log");
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);
  return status == 0;
}

std::string gnuplot_problem(PlotFormat format) {
  if (!gnuplot_available()) return "gnuplot is not installed (apt-get install gnuplot-nox)";
  if (!gnuplot_supports(format)) {
    return std::string("the installed gnuplot has no ") + gnuplot_terminal_name(format) +
           " terminal (apt-get install gnuplot-nox, which is built with cairo)";
  }
  return "";
}

std::string gnuplot_terminal(PlotFormat format, int width_px, int height_px) {
  const std::string size = std::to_string(width_px) + "," + std::to_string(height_px);
  if (format == PlotFormat::Png) {
    return "set terminal pngcairo size " + size +
           " noenhanced font 'Helvetica,10' background rgb 'white'\n";
  }
  return "set terminal svg size " + size +
         " dynamic noenhanced font 'Helvetica,12' background rgb 'white'\n";
}

std::string gnuplot_quote(const std::string& text) {
  // Double-quoted gnuplot strings run `backquoted` commands; single-quoted ones are taken
  // literally. A quote and a line break cannot be written inside them (gnuplot 5.4 misreads
  // the doubled quote '' when two follow each other), so each is a double-quoted piece of its
  // own, without backquotes, joined by gnuplot's string concatenation.
  std::string out = "'";
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\'') {
      out += "'.\"'\".'";
    } else if (c == '\n') {
      out += "'.\"\\n\".'";
    } else if (u < 0x20 || u == 0x7f) {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string gnuplot_quote_tic_label(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '%') escaped += '%';
    escaped += c;
  }
  return gnuplot_quote(escaped);
}

void check_plot_complete(const std::filesystem::path& file, PlotFormat format) {
  std::ifstream in(file, std::ios::binary);
  std::string tail;
  if (in) {
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    const std::streamoff n = std::min<std::streamoff>(size, 64);
    in.seekg(size - n);
    tail.resize(static_cast<std::size_t>(n));
    in.read(tail.data(), n);
    if (!in) tail.clear();
  }
  while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back()))) tail.pop_back();
  static const std::string png_end("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  const bool complete =
      format == PlotFormat::Png
          ? tail.size() >= png_end.size() &&
                tail.compare(tail.size() - png_end.size(), png_end.size(), png_end) == 0
          : tail.size() >= 6 && tail.compare(tail.size() - 6, 6, "</svg>") == 0;
  if (!complete) {
    throw std::runtime_error(std::string("gnuplot left an incomplete ") +
                             (format == PlotFormat::Png ? "PNG" : "SVG") +
                             " file (is the disk full?)");
  }
}

void run_gnuplot(const std::string& script,
                 const std::vector<std::pair<std::string, std::string>>& data_files) {
  const auto dir = fresh_temp_dir("ecorail-plot-");
  try {
    for (const auto& [name, content] : data_files) {
      std::ofstream out(dir / name, std::ios::binary);
      out << content;
      if (!out.flush()) throw std::runtime_error("cannot write the plot data");
    }
    {
      std::ofstream gp(dir / "plot.gp");
      gp << script;
      if (!gp.flush()) throw std::runtime_error("cannot write the plot script");
    }
    if (run_program({"gnuplot", "plot.gp"}, dir, dir / "gnuplot.log") != 0) {
      std::ifstream log(dir / "gnuplot.log");
      std::stringstream msg;
      msg << log.rdbuf();
      std::string text = msg.str();
      // One line: the caller's error message is printed as one line.
      std::replace(text.begin(), text.end(), '\n', ' ');
      throw std::runtime_error("gnuplot failed: " + text);
    }
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
    throw;
  }
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);
}

}  // namespace ecorail::output
