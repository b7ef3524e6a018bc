// tandem view: the interactive viewer (viewer_app.cpp). Built when GLFW, Dear ImGui and OpenGL
// are found; otherwise the verb explains what is missing.
#include "cli_options.h"
#include "core/error.h"
#include "verbs.h"
#ifdef TANDEM_HAVE_VIEWER
#include "viewer_app.h"
#endif

namespace tandem {

VerbRunner addViewVerb(CLI::App& app) {
  struct Args {
    RenderOptions render;
    std::string screenshot, windowCapture;
    bool exitAfter = false, hideUi = false;
    float scale = 1.0f;
  };
  auto a = std::make_shared<Args>();
  a->render.width = 1280;
  a->render.height = 720;
  CLI::App* sub = app.add_subcommand(
      "view", "Interactive viewer: fly through a scene, switch pipelines, tune passes");
  addRenderOptions(sub, a->render);
  sub->add_option("--screenshot", a->screenshot, "Write the output as PNG after --frames frames");
  sub->add_option("--window-capture", a->windowCapture,
                  "Write what the window shows as PNG after --frames frames");
  sub->add_option("--scale", a->scale, "Render resolution / window resolution (0.05-2)");
  sub->add_flag("--exit", a->exitAfter, "Quit after --frames frames and the screenshots");
  sub->add_flag("--hide-ui", a->hideUi, "No panels (for captures of the image alone)");
  return [a, sub]() -> int {
#ifdef TANDEM_HAVE_VIEWER
    ViewerOptions o;
    o.render = a->render;
    o.screenshot = a->screenshot;
    o.windowCapture = a->windowCapture;
    // Without --frames, scripted runs (screenshot, capture, exit) wait for 3 frames.
    const bool scripted = !a->screenshot.empty() || !a->windowCapture.empty() || a->exitAfter;
    o.frames = sub->count("--frames") > 0 ? a->render.frames : scripted ? 3 : 0;
    o.exitAfter = a->exitAfter;
    o.hideUi = a->hideUi;
    o.scale = a->scale;
    return runViewer(o);
#else
    throw InputError("tandem view", "build",
                     "this tandem was built without the viewer (needs libglfw3-dev, "
                     "libimgui-dev and OpenGL; scripts/install-deps.sh installs them); use "
                     "`tandem render` to write images");
#endif
  };
}

}  // namespace tandem
