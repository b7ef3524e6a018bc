// The viewer's ImGui panels: view and camera, pipeline and passes (widgets generated from each
// pass's parameter table), buffers, and the profiler.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/image_io.h"
#include "scene/camera_json.h"
#include "viewer/param_widgets.h"
#include "viewer_app.h"

namespace tandem {

namespace {

void tooltip(const std::string& text) {
  if (!text.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
}

bool inputText(const char* label, std::string& value) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s", value.c_str());
  if (!ImGui::InputText(label, buf, sizeof buf)) return false;
  value = buf;
  return true;
}

// One generated widget; returns true (and the new value) when the user changed it.
bool drawWidget(const ParamWidget& w, double& value) {
  bool changed = false;
  switch (w.kind) {
    case WidgetKind::Checkbox: {
      bool b = value != 0;
      changed = ImGui::Checkbox(w.label.c_str(), &b);
      value = b ? 1 : 0;
      break;
    }
    case WidgetKind::Combo: {
      int i = int(value);
      if (ImGui::BeginCombo(w.label.c_str(), w.choices.at(size_t(i)).c_str())) {
        for (size_t c = 0; c < w.choices.size(); ++c)
          if (ImGui::Selectable(w.choices[c].c_str(), int(c) == i)) i = int(c), changed = true;
        ImGui::EndCombo();
      }
      value = i;
      break;
    }
    case WidgetKind::SliderInt:
    case WidgetKind::DragInt: {
      int i = int(value);
      changed = w.kind == WidgetKind::SliderInt
                    ? ImGui::SliderInt(w.label.c_str(), &i, int(w.min), int(w.max))
                    : ImGui::DragInt(w.label.c_str(), &i, 1.0f, int(w.min), int(w.max));
      value = std::clamp(double(i), w.min, w.max);
      break;
    }
    case WidgetKind::SliderFloat:
    case WidgetKind::SliderFloatLog:
    case WidgetKind::DragFloat: {
      float f = float(value);
      if (w.kind == WidgetKind::DragFloat)
        changed =
            ImGui::DragFloat(w.label.c_str(), &f, float(std::max(std::abs(value), 1.0) * 0.01),
                             float(w.min), float(w.max), "%.4g");
      else
        changed =
            ImGui::SliderFloat(w.label.c_str(), &f, float(w.min), float(w.max), "%.4g",
                               w.kind == WidgetKind::SliderFloatLog ? ImGuiSliderFlags_Logarithmic
                                                                    : ImGuiSliderFlags_None);
      value = std::clamp(double(f), w.min, w.max);
      break;
    }
  }
  tooltip(w.tooltip);
  return changed;
}

void viewPanel(ViewerState& s, RenderWorker& worker) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Tandem");
  ImGui::Text("%s: %dx%d  %.1f fps  %.1f ms", s.pipelineName.c_str(), s.frame.width, s.frame.height,
              s.history.framesPerSecond(), s.history.averageFrameMs());
  if (s.frame.samplesPerPixel > 0) ImGui::Text("progressive: %d spp", s.frame.samplesPerPixel);
  ImGui::Text("viewer: upload + UI %.2f ms, present %.2f ms", s.viewerMs, s.presentMs);
  if (!worker.error().empty())
    ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", worker.error().c_str());
  if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());

  // Pipelines: any built-in, or a JSON file; switching rebuilds on the worker, no restart.
  if (ImGui::BeginCombo("pipeline", s.pipelineName.c_str())) {
    for (const std::string& name : Pipeline::builtinNames())
      if (ImGui::Selectable(name.c_str(), name == s.pipelineName)) {
        s.model = PipelineModel::load(name);
        for (auto& p : s.model.passes)
          if (p.values.count("accumulate")) p.values["accumulate"] = 1, p.values["progress"] = 0;
        s.pipelineName = name;
        s.view.shownBuffer.clear();
        worker.setPipeline(s.model);
        worker.setView(s.view);
      }
    ImGui::EndCombo();
  }
  static std::string pipelineFile;
  inputText("##pipefile", pipelineFile);
  ImGui::SameLine();
  if (ImGui::Button("load JSON")) {
    try {
      s.model = PipelineModel::load(pipelineFile);
      s.pipelineName = pipelineFile;
      worker.setPipeline(s.model);
      s.message = "loaded " + pipelineFile;
    } catch (const std::exception& e) {
      s.message = e.what();
    }
  }

  // Buffers: the output or any named buffer, with a view per kind.
  const std::string shown = s.view.shownBuffer.empty() ? "output" : s.view.shownBuffer;
  if (ImGui::BeginCombo("buffer", shown.c_str())) {
    if (ImGui::Selectable("output", s.view.shownBuffer.empty())) s.view.shownBuffer.clear();
    for (const std::string& b : s.frame.buffers)
      if (ImGui::Selectable(b.c_str(), b == s.view.shownBuffer)) s.view.shownBuffer = b;
    ImGui::EndCombo();
  }
  if (s.view.shownBuffer == "variance")
    ImGui::SliderFloat("variance scale", &s.view.varianceScale, 0.1f, 1000.0f, "%.1f",
                       ImGuiSliderFlags_Logarithmic);
  ImGui::SliderFloat("resolution scale", &s.opts.scale, 0.1f, 2.0f, "%.2f");

  // Camera.
  if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextWrapped("WASD move, Q/E down/up, shift faster, right mouse button look");
    ImGui::SliderFloat("speed (m/s)", &s.fly.speed, 0.01f, 100.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    if (ImGui::Button("reset")) s.fly = FlyCamera::fromDesc(s.startCamera), s.playing = false;
    ImGui::SameLine();
    ImGui::Text("pos %.2f %.2f %.2f", s.fly.position.x, s.fly.position.y, s.fly.position.z);
    inputText("camera file", s.cameraFile);
    if (ImGui::Button("save camera + path")) saveCamera(s);
    ImGui::SameLine();
    if (ImGui::Button("load camera + path")) loadCamera(s);
    if (!s.recording && ImGui::Button("record path")) {
      s.path.clear();
      s.recording = true;
      s.recordStart = ImGui::GetTime();
      s.lastKey = -1;
    } else if (s.recording && ImGui::Button("stop recording")) {
      s.recording = false;
    }
    ImGui::SameLine();
    if (s.path.size() >= 2 && ImGui::Button(s.playing ? "stop" : "play path")) {
      s.playing = !s.playing;
      s.playStart = ImGui::GetTime();
    }
    ImGui::SameLine();
    ImGui::Text("%zu keys", s.path.size());
    if (!s.scene->cameraPath.empty() && ImGui::Button("use the scene's path (bench)")) {
      s.path = s.scene->cameraPath;
      s.message = "path: the scene's camera path, " + std::to_string(s.path.size()) + " keys";
    }
  }
  if (ImGui::CollapsingHeader("Files")) {
    inputText("pipeline JSON", s.pipelineFile);
    if (ImGui::Button("save pipeline with current parameters")) {
      try {
        std::filesystem::path p(s.pipelineFile);
        if (!p.parent_path().empty()) std::filesystem::create_directories(p.parent_path());
        Pipeline built = s.model.build();
        built.name = std::filesystem::path(s.pipelineFile).stem().string();
        writeTextFile(s.pipelineFile, built.toJson().dump(2) + "\n");
        s.message = "wrote " + s.pipelineFile;
      } catch (const std::exception& e) {
        s.message = e.what();
      }
    }
    inputText("screenshot", s.screenshotFile);
    if (ImGui::Button("screenshot (F12)")) saveScreenshot(s, s.screenshotFile);
  }
  ImGui::End();
}

void passesPanel(ViewerState& s, RenderWorker& worker) {
  ImGui::SetNextWindowPos(ImVec2(8, 420), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 300), ImGuiCond_FirstUseEver);
  ImGui::Begin("Passes");
  Pipeline reference = Pipeline::load(s.model.source);  // declared parameter tables
  for (size_t i = 0; i < s.model.passes.size() && i < reference.passes.size(); ++i) {
    auto& pm = s.model.passes[i];
    ImGui::PushID(int(i));
    if (ImGui::Checkbox("##on", &pm.enabled)) worker.setEnabled(i, pm.enabled);
    tooltip("enable (a disabled pass passes its input through)");
    ImGui::SameLine();
    if (ImGui::TreeNodeEx(pm.label.c_str(), ImGuiTreeNodeFlags_DefaultOpen, "%zu. %s", i + 1,
                          pm.label.c_str())) {
      tooltip(reference.passes[i]->description());
      for (const ParamWidget& w : paramWidgets(*reference.passes[i])) {
        double v = pm.values[w.param];
        if (drawWidget(w, v)) {
          pm.values[w.param] = v;
          worker.setParam(i, w.param, v);
        }
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  ImGui::End();
}

void profilerPanel(ViewerState& s) {
  ImGui::SetNextWindowPos(ImVec2(350, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(470, 340), ImGuiCond_FirstUseEver);
  ImGui::Begin("Profiler");
  ImGui::Text("%.1f fps, frame %.2f ms (mean of %zu)", s.history.framesPerSecond(),
              s.history.averageFrameMs(), s.history.size());
  const auto rows = s.history.rows();
  if (ImGui::BeginTable("passes", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_Borders)) {
    ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch, 2.0f);
    ImGui::TableSetupColumn("ms", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("mean ms", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("Mrays/s", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableHeadersRow();
    for (const auto& r : rows) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(r.name.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", r.currentMs);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", r.averageMs);
      ImGui::TableNextColumn();
      if (r.raysPerSecond > 0) ImGui::Text("%.2f", r.raysPerSecond * 1e-6);
    }
    ImGui::EndTable();
  }
  // Stacked graph: one column per frame, one colour per top-level pass.
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 110);
  const ImVec2 o = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(o, ImVec2(o.x + size.x, o.y + size.y), IM_COL32(20, 20, 24, 255));
  double maxMs = 1;
  for (const FrameTimings& f : s.history.frames()) maxMs = std::max(maxMs, f.totalMs);
  const size_t n = s.history.frames().size();
  const float colW = n ? size.x / float(n) : size.x;
  size_t k = 0;
  for (const FrameTimings& f : s.history.frames()) {
    float y = o.y + size.y;
    int c = 0;
    for (const PassTiming& p : f.passes) {
      if (p.name.find('/') != std::string::npos) continue;  // parts are inside their pass
      const float h = float(p.ms / maxMs) * size.y;
      const ImU32 col = ImColor::HSV(float(c++) * 0.13f, 0.6f, 0.9f);
      dl->AddRectFilled(ImVec2(o.x + float(k) * colW, y - h), ImVec2(o.x + float(k + 1) * colW, y),
                        col);
      y -= h;
    }
    ++k;
  }
  ImGui::Dummy(size);
  int c = 0;
  for (const auto& r : rows) {
    if (r.name.find('/') != std::string::npos) continue;
    ImGui::ColorButton(r.name.c_str(), ImColor::HSV(float(c++) * 0.13f, 0.6f, 0.9f),
                       ImGuiColorEditFlags_NoTooltip, ImVec2(10, 10));
    ImGui::SameLine();
    ImGui::Text("%s", r.name.c_str());
  }
  ImGui::Text("graph height = %.1f ms", maxMs);
  ImGui::End();
}

}  // namespace

void saveCamera(ViewerState& s) {
  try {
    Json j;
    namespace fs = std::filesystem;
    const std::string& scene = s.opts.render.scene;
    j["base"] = fs::exists(scene) ? fs::absolute(scene).string() : scene;
    j["camera"] = cameraToJson(s.fly.toDesc(s.baseCamera));
    if (!s.path.empty()) j["cameraPath"] = cameraPathToJson(s.path);
    fs::path p(s.cameraFile);
    if (!p.parent_path().empty()) fs::create_directories(p.parent_path());
    writeTextFile(s.cameraFile, j.dump(2) + "\n");
    s.message = "wrote " + s.cameraFile + " (a scene file: `tandem render " + s.cameraFile + "`)";
  } catch (const std::exception& e) {
    s.message = e.what();
  }
}

void loadCamera(ViewerState& s) {
  try {
    std::ifstream in(s.cameraFile);
    if (!in) throw InputError(s.cameraFile, "", "cannot open");
    const Json j = Json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.is_object()) throw InputError(s.cameraFile, "", "not a JSON object");
    if (j.contains("camera"))
      s.fly = FlyCamera::fromDesc(cameraFromJson(j["camera"], s.cameraFile, s.baseCamera));
    if (j.contains("cameraPath"))
      s.path = cameraPathFromJson(j["cameraPath"], s.cameraFile, s.baseCamera);
    s.message = "loaded " + s.cameraFile;
  } catch (const std::exception& e) {
    s.message = e.what();
  }
}

void drawPanels(ViewerState& s, RenderWorker& worker) {
  viewPanel(s, worker);
  passesPanel(s, worker);
  profilerPanel(s);
}

}  // namespace tandem
