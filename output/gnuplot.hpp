// Running gnuplot for the plots: its presence and that of a terminal, the output format chosen by
// the file name (.svg or .png, through gnuplot's svg and pngcairo terminals), the one quoting
// helper through which every piece of text (titles, labels, station names, file names) reaches
// a script, and running a script in a private temporary directory with its data files. gnuplot
// runs commands from text it is given (backquotes inside double-quoted strings, system()), so
// no string may reach a script except through gnuplot_quote, and gnuplot itself is started
// without a shell.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ecorail::output {

enum class PlotFormat { Svg, Png };

// The format a plot path asks for: ".svg" or ".png" (any case); "-" (standard output) is SVG.
// nullopt for any other name: a plot is never written in a format its name does not say.
std::optional<PlotFormat> plot_format_for(const std::filesystem::path& path);
bool gnuplot_available();
// Whether the installed gnuplot knows the terminal of format (svg, pngcairo): a gnuplot built
// without cairo cannot write PNG, and a plot must be refused before any work, not after it.
bool gnuplot_supports(PlotFormat format);
// Why a plot of format cannot be drawn ("gnuplot is not installed ...", "the installed gnuplot
// has no pngcairo terminal ..."), or "" when it can.
std::string gnuplot_problem(PlotFormat format);
// The gnuplot terminal name of a format ("svg", "pngcairo").
const char* gnuplot_terminal_name(PlotFormat format);
// The "set terminal" line of the format (text drawn literally: no enhanced-text markup).
std::string gnuplot_terminal(PlotFormat format, int width_px, int height_px);
// text as a gnuplot string expression that evaluates to text and nothing else: single-quoted
// pieces (gnuplot does no substitution inside them) joined by "'" and "\n" where text has
// quotes and line breaks; other control characters become spaces.
std::string gnuplot_quote(const std::string& text);
// gnuplot_quote for the label of an explicit tic ("set xtics ('A7' 1354)"): gnuplot reads such
// a label as a format for the tic's value, so a '%' is doubled to stand for itself.
std::string gnuplot_quote_tic_label(const std::string& text);

// Throws unless file is a complete plot of format: an SVG ending in </svg>, a PNG ending in its
// IEND chunk. gnuplot can exit 0 after writing part of a file (a full disk), and a truncated
// plot must not be committed as a result.
void check_plot_complete(const std::filesystem::path& file, PlotFormat format);

// Writes the named data files and the script into a fresh temporary directory, runs gnuplot
// there without a shell (the script names the data files bare, and its output file by an
// absolute path) and removes the directory. gnuplot is killed if this process dies. Throws with
// gnuplot's messages when it fails.
void run_gnuplot(const std::string& script,
                 const std::vector<std::pair<std::string, std::string>>& data_files);

}  // namespace ecorail::output
