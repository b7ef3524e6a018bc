#include "eval/experiments/experiment_report.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/image_io.h"

namespace tandem {
namespace fs = std::filesystem;

std::string fmt(double v, int decimals) {
  if (std::isinf(v)) return "inf";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

std::string sceneLabel(const std::string& spec) {
  return fs::path(spec).stem().string();
}

void cropFromJson(JsonFields& f, int crop[4]) {
  if (!f.has("crop")) return;
  const Json& c = f.raw("crop");
  if (!c.is_array() || c.size() != 4) f.fail("crop", "expected [x, y, width, height]");
  for (int k = 0; k < 4; ++k) {
    if (!c[size_t(k)].is_number_integer() || c[size_t(k)].get<int>() < 0)
      f.fail("crop", "expected non-negative integers");
    crop[k] = c[size_t(k)].get<int>();
  }
}

void scenePairsFromJson(JsonFields& f, std::vector<std::string>& labels,
                        std::vector<std::string>& scenes) {
  if (!f.has("scenes") || !f.raw("scenes").is_array() || f.raw("scenes").empty())
    f.fail("scenes", "expected an array of [label, scene] pairs");
  const fs::path base = fs::path(f.file()).parent_path();
  for (const Json& s : f.raw("scenes")) {
    if (!s.is_array() || s.size() != 2 || !s[0].is_string() || !s[1].is_string())
      f.fail("scenes", "each scene is [label, scene name or file]");
    std::string path = s[1].get<std::string>();
    if (path.find('.') != std::string::npos && fs::path(path).is_relative())
      path = (base / path).string();
    labels.push_back(s[0].get<std::string>());
    scenes.push_back(path);
  }
}

Buffer cropOf(const Buffer& b, const int c[4]) {
  int x = c[0], y = c[1], w = c[2], h = c[3];
  if (w == 0 || h == 0) x = b.width / 3, y = b.height / 3, w = b.width / 3, h = b.height / 3;
  x = std::min(x, b.width - 1);
  y = std::min(y, b.height - 1);
  w = std::min(w, b.width - x);
  h = std::min(h, b.height - y);
  Buffer out(w, h, b.channels, 0.0f, b.kind);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int k = 0; k < b.channels; ++k) out.at(i, j)[k] = b.at(x + i, y + j)[k];
  return out;
}

ExperimentReport::ExperimentReport(fs::path dir, std::string title)
    : dir_(std::move(dir)), title_(std::move(title)), machine_(machineInfo()) {
  if (!dir_.empty()) fs::create_directories(dir_);
}

namespace {

// One CSV field (RFC 4180): quoted when it holds a comma, a quote or a line break.
std::string csvField(const std::string& v) {
  if (v.find_first_of(",\"\n\r") == std::string::npos) return v;
  std::string q = "\"";
  for (char c : v) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

void ExperimentReport::table(const std::string& name, const std::vector<std::string>& header,
                             const std::vector<std::vector<std::string>>& rows) {
  std::ostringstream csv, md;
  for (size_t i = 0; i < header.size(); ++i) csv << (i ? "," : "") << csvField(header[i]);
  csv << "\n";
  md << "|";
  for (const std::string& h : header) md << " " << h << " |";
  md << "\n|";
  for (size_t i = 0; i < header.size(); ++i) md << (i ? " ---: |" : " --- |");
  md << "\n";
  for (const auto& row : rows) {
    md << "|";
    for (size_t i = 0; i < row.size(); ++i) {
      csv << (i ? "," : "") << csvField(row[i]);
      md << " " << row[i] << " |";
    }
    csv << "\n";
    md << "\n";
  }
  writeTextFile((dir_ / (name + ".csv")).string(), csv.str());
  md_ += md.str() + "\n(`" + name + ".csv`)\n\n";
}

namespace {
std::string quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return q + "\"";
}
}  // namespace

void ExperimentReport::plot(const std::string& name, const std::string& title,
                            const std::string& xLabel, const std::string& yLabel,
                            const std::vector<PlotSeries>& series, bool logX, bool logY) {
  std::ostringstream dat, gp;
  // One gnuplot data block per series (separated by two blank lines: `index i`).
  for (const PlotSeries& s : series) {
    dat << "# " << s.label << "\n";
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) dat << s.x[i] << " " << s.y[i] << "\n";
    dat << "\n\n";
  }
  const std::string datFile = name + ".dat", pngFile = name + ".png";
  gp << "set terminal pngcairo noenhanced size 720,440 font 'sans,10'\nset output "
     << quote(pngFile) << "\nset title " << quote(title) << "\nset xlabel " << quote(xLabel)
     << "\nset ylabel " << quote(yLabel) << "\nset grid\nset key outside right\n"
     << (logX ? "set logscale x\n" : "") << (logY ? "set logscale y\n" : "") << "plot ";
  for (size_t i = 0; i < series.size(); ++i)
    gp << (i ? ", " : "") << quote(datFile) << " index " << i << " with linespoints lw 2 title "
       << quote(series[i].label);
  gp << "\n";
  writeTextFile((dir_ / datFile).string(), dat.str());
  writeTextFile((dir_ / (name + ".gp")).string(), gp.str());
  // gnuplot runs in the folder so the script's relative names resolve; its absence is not an
  // error (the data and script stay for later).
  const std::string cmd = "cd " + quote(dir_.empty() ? "." : dir_.string()) + " && gnuplot " +
                          quote(name + ".gp") + " >/dev/null 2>&1";
  if (std::system(cmd.c_str()) == 0 && fs::exists(dir_ / pngFile)) {
    plots_.push_back({pngFile, title});
    md_ += "![" + title + "](" + pngFile + ")\n\n";
  } else {
    md_ += "Plot `" + name + "` not drawn (gnuplot missing); data in `" + datFile + "`, script `" +
           name + ".gp`.\n\n";
  }
}

void ExperimentReport::image(const std::string& file, const std::string& caption) {
  images_.push_back({file, caption});
}

void ExperimentReport::write(const std::string& settings) {
  std::ostringstream md;
  md << "# " << title_ << "\n\nMachine: " << machine_.oneLine() << ".\n\n"
     << settings << "\n\n"
     << md_;
  writeTextFile((dir_ / "results.md").string(), md.str());

  auto esc = [](const std::string& s) {
    std::string o;
    for (char c : s)
      o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    return o;
  };
  std::ostringstream html;
  html << "<!doctype html><html><head><meta charset='utf-8'><title>" << esc(title_)
       << "</title><style>body{font-family:sans-serif;max-width:1200px;margin:auto}"
          "figure{display:inline-block;margin:4px;vertical-align:top}"
          "figcaption{font-size:12px}img{max-width:380px}pre{background:#f4f4f4;padding:8px;"
          "overflow:auto}</style></head><body>\n<h1>"
       << esc(title_) << "</h1>\n<p>Machine: " << esc(machine_.oneLine()) << "</p>\n<p>"
       << esc(settings) << "</p>\n<p><a href='results.md'>results.md</a></p>\n";
  if (!plots_.empty()) {
    html << "<h2>Plots</h2>\n";
    for (const auto& [file, caption] : plots_)
      html << "<figure><img src='" << file << "' style='max-width:720px'><figcaption>"
           << esc(caption) << "</figcaption></figure>\n";
  }
  html << "<h2>Tables</h2>\n<pre>" << esc(md_) << "</pre>\n";
  if (!images_.empty()) {
    html << "<h2>Images</h2>\n";
    for (const auto& [file, caption] : images_)
      html << "<figure><a href='" << file << "'><img src='" << file << "'></a><figcaption>"
           << esc(caption) << "</figcaption></figure>\n";
  }
  html << "</body></html>\n";
  writeTextFile((dir_ / "index.html").string(), html.str());
}

}  // namespace tandem
