#pragma once
// Figures drawn by gnuplot from a table written beside them (docs/DESIGN.md: every figure is drawn
// from a table). For a figure NAME the folder gets NAME.dat (the numbers), NAME.gp (the script,
// which reads only NAME.dat) and NAME.png, so a user can edit the script and replot with
// `gnuplot NAME.gp` in that folder.
//
// NAME.dat is gnuplot's plain-text format: whitespace columns, blocks separated by two blank
// lines (gnuplot's `index`). Each block opens with a comment saying what it holds and a comment
// naming its columns with their units ("# t_ms z_left_mm"). Missing values are written as NaN,
// which gnuplot treats as a break in a line.
#include <string>
#include <vector>

namespace dimer::compare {

struct DataBlock {
  std::string comment;                    // what the block holds (one line)
  std::vector<std::string> columns;       // names with units, e.g. "t_ms"; no spaces
  std::vector<std::vector<double>> rows;  // each as long as `columns`
};

struct Figure {
  std::string name;             // file stem: NAME.dat, NAME.gp, NAME.png
  int width_px = 1000, height_px = 600;
  std::vector<DataBlock> blocks;
  std::string script;           // gnuplot commands after the terminal and output lines
};

// Writes `path` (blocks as described above, numbers with 9 significant digits).
void WriteDataFile(const std::string& path, const std::vector<DataBlock>& blocks);

// Writes dir/NAME.dat and dir/NAME.gp, then runs gnuplot to draw dir/NAME.png. Throws
// std::runtime_error naming the script (with gnuplot's own message) when gnuplot is missing,
// fails or draws nothing. Returns gnuplot's warnings (its stderr on success), usually empty.
std::string DrawFigure(const std::string& dir, const Figure& figure);

// Runs `gnuplot script` with `dir` as working directory; errors as DrawFigure.
std::string RunGnuplot(const std::string& dir, const std::string& script);

// `text` as a gnuplot double-quoted string (quotes and backslashes escaped).
std::string GnuplotQuote(const std::string& text);

}  // namespace dimer::compare
