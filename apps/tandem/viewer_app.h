// `tandem view`: the interactive viewer (GLFW window, OpenGL 3.3 core, Dear ImGui panels). The
// pipeline renders on a RenderWorker thread; the window shows the last finished frame.
#pragma once
#include <string>
#include <vector>

#include "cli_options.h"
#include "viewer/fly_camera.h"
#include "viewer/frame_history.h"
#include "viewer/render_worker.h"

namespace tandem {

struct ViewerOptions {
  RenderOptions render;       // scene, pipeline, window size, camera, lights, --set
  std::string screenshot;     // write the output as PNG after `frames` frames
  std::string windowCapture;  // write what the window shows (the drawn image) as PNG
  int frames = 0;             // frames to render before screenshots / exit
  bool exitAfter = false;     // --exit: quit once the frames and screenshots are done
  bool hideUi = false;        // no panels (captures of the image alone)
  float scale = 1.0f;         // render resolution / window resolution
};

// Everything the panels read and change.
struct ViewerState {
  ViewerOptions opts;
  const Scene* scene = nullptr;
  CameraDesc baseCamera, startCamera;
  FlyCamera fly;
  ViewState view;
  PipelineModel model;
  std::string pipelineName;
  FinishedFrame frame;
  FrameHistory history{120};
  float viewerMs = 0;      // upload + UI of the last displayed frame
  double viewerMsSum = 0;  // for the average printed at exit
  int viewerFrames = 0;
  float presentMs = 0;  // buffer swap of the last displayed frame (the GL driver's drawing)
  double presentMsSum = 0;
  std::string message;  // last status line (saved, loaded, errors)
  // Camera path recording and playback (scene-file cameraPath keys).
  std::vector<CameraKey> path;
  bool recording = false, playing = false;
  double recordStart = 0, playStart = 0, lastKey = -1;
  std::string cameraFile = "out/view_camera.json", pipelineFile = "out/view_pipeline.json";
  std::string screenshotFile = "out/view_screenshot.png";
};

// Builds the ImGui panels for one frame; changes go to `worker`.
void drawPanels(ViewerState& s, RenderWorker& worker);
// Saves the current output as PNG (F12 and the panel's button).
void saveScreenshot(ViewerState& s, const std::string& path);
// Camera and path in the scene file format: {"base": scene, "camera": ..., "cameraPath": ...}.
void saveCamera(ViewerState& s);
void loadCamera(ViewerState& s);

int runViewer(const ViewerOptions& o);

}  // namespace tandem
