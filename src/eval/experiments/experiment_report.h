// What every experiment writes into its folder: results.md (Markdown tables), one CSV per table,
// PNG plots (drawn by gnuplot from the .dat and .gp files kept beside them, so a plot can be
// restyled and redrawn), images, and index.html tying them together with the machine, build and
// commit that produced them.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/buffer.h"
#include "core/json_fields.h"
#include "eval/experiments/machine_info.h"

namespace tandem {

std::string fmt(double v, int decimals = 2);
// A short label for a scene spec (file stem or built-in name).
std::string sceneLabel(const std::string& spec);
// A crop (x, y, width, height; width or height 0: the centre third) of an image, clamped to it.
Buffer cropOf(const Buffer& b, const int crop[4]);
// An experiment file's optional "crop": [x, y, width, height] of non-negative integers.
void cropFromJson(JsonFields& f, int crop[4]);
// An experiment file's "scenes": [[label, scene name or file], ...]; relative files are taken
// from the experiment file's folder.
void scenePairsFromJson(JsonFields& f, std::vector<std::string>& labels,
                        std::vector<std::string>& scenes);

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
};

class ExperimentReport {
 public:
  ExperimentReport(std::filesystem::path dir, std::string title);

  // Free Markdown (also shown on the index page as preformatted text).
  void markdown(const std::string& text) { md_ += text; }
  // A table: written as <name>.csv and as a Markdown table in results.md.
  void table(const std::string& name, const std::vector<std::string>& header,
             const std::vector<std::vector<std::string>>& rows);
  // A line plot <name>.png of y against x, one line per series (gnuplot; skipped with a note in
  // results.md when gnuplot is not installed).
  void plot(const std::string& name, const std::string& title, const std::string& xLabel,
            const std::string& yLabel, const std::vector<PlotSeries>& series, bool logX = false,
            bool logY = false);
  // An image already written into the folder, listed on the index page.
  void image(const std::string& file, const std::string& caption);
  // Writes results.md and index.html.
  void write(const std::string& settings);

  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::string title_, md_;
  MachineInfo machine_;
  std::vector<std::pair<std::string, std::string>> images_, plots_;
};

}  // namespace tandem
