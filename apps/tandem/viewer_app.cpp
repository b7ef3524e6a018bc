#include "viewer_app.h"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

#include "core/error.h"
#include "core/image_io.h"
#include "core/profiler.h"
#include "pipeline/renderer.h"

namespace tandem {

namespace {

constexpr double kDisplayHz = 60;  // window refresh cap; frames come from the worker

std::string glfwProblem;
void onGlfwError(int code, const char* text) {
  glfwProblem = "GLFW error " + std::to_string(code) + ": " + (text ? text : "");
}

// Input marks the window for redrawing for a few refreshes (ImGui needs a frame or two to react);
// otherwise the window is redrawn only when the worker has finished a new frame. ImGui's GLFW
// backend chains to these callbacks, which are installed before it.
int redrawsPending = 2;
void markInput(GLFWwindow*) {
  redrawsPending = 3;
}
void installRedrawCallbacks(GLFWwindow* w) {
  glfwSetCursorPosCallback(w, [](GLFWwindow* x, double, double) { markInput(x); });
  glfwSetMouseButtonCallback(w, [](GLFWwindow* x, int, int, int) { markInput(x); });
  glfwSetScrollCallback(w, [](GLFWwindow* x, double, double) { markInput(x); });
  glfwSetKeyCallback(w, [](GLFWwindow* x, int, int, int, int) { markInput(x); });
  glfwSetCharCallback(w, [](GLFWwindow* x, unsigned) { markInput(x); });
  glfwSetWindowFocusCallback(w, [](GLFWwindow* x, int) { markInput(x); });
  glfwSetCursorEnterCallback(w, [](GLFWwindow* x, int) { markInput(x); });
  glfwSetFramebufferSizeCallback(w, [](GLFWwindow* x, int, int) { markInput(x); });
  glfwSetWindowRefreshCallback(w, markInput);
}

// What the window shows: the frame's image over the whole framebuffer (the render is the
// window size times the resolution scale). Copied with a framebuffer blit, not drawn as a
// blended, filtered quad: on a software GL (Mesa llvmpipe under Xvfb) the quad cost the
// renderer's cores several milliseconds a frame. Linear filtering only when the sizes differ.
struct ImageBlit {
  using GenFramebuffers = void (*)(GLsizei, GLuint*);
  using BindFramebuffer = void (*)(GLenum, GLuint);
  using FramebufferTexture2D = void (*)(GLenum, GLenum, GLenum, GLuint, GLint);
  using BlitFramebuffer = void (*)(GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint,
                                   GLbitfield, GLenum);
  GenFramebuffers genFramebuffers = nullptr;
  BindFramebuffer bindFramebuffer = nullptr;
  FramebufferTexture2D framebufferTexture2D = nullptr;
  BlitFramebuffer blitFramebuffer = nullptr;
  GLuint fbo = 0;

  void init(GLuint tex) {
    genFramebuffers = reinterpret_cast<GenFramebuffers>(glfwGetProcAddress("glGenFramebuffers"));
    bindFramebuffer = reinterpret_cast<BindFramebuffer>(glfwGetProcAddress("glBindFramebuffer"));
    framebufferTexture2D =
        reinterpret_cast<FramebufferTexture2D>(glfwGetProcAddress("glFramebufferTexture2D"));
    blitFramebuffer = reinterpret_cast<BlitFramebuffer>(glfwGetProcAddress("glBlitFramebuffer"));
    if (!genFramebuffers || !bindFramebuffer || !framebufferTexture2D || !blitFramebuffer)
      throw std::runtime_error("the OpenGL driver lacks framebuffer objects (OpenGL 3.0)");
    genFramebuffers(1, &fbo);
    bindFramebuffer(0x8CA8 /* GL_READ_FRAMEBUFFER */, fbo);
    framebufferTexture2D(0x8CA8, 0x8CE0 /* GL_COLOR_ATTACHMENT0 */, GL_TEXTURE_2D, tex, 0);
    bindFramebuffer(0x8CA8, 0);
  }
  // The texture's rows are top first; the window's bottom first: the blit flips them.
  void draw(int texWidth, int texHeight, int fbWidth, int fbHeight) const {
    bindFramebuffer(0x8CA8, fbo);
    bindFramebuffer(0x8CA9 /* GL_DRAW_FRAMEBUFFER */, 0);
    const bool same = texWidth == fbWidth && texHeight == fbHeight;
    blitFramebuffer(0, texHeight, texWidth, 0, 0, 0, fbWidth, fbHeight, GL_COLOR_BUFFER_BIT,
                    same ? GL_NEAREST : GL_LINEAR);
    bindFramebuffer(0x8CA8, 0);
  }
};

// The window refreshes at most kDisplayHz: without a cap the loop spins and, on a software GL
// (Mesa llvmpipe), redraws the window as fast as it can on the cores the renderer needs.
void waitForNextRefresh(double loopStart) {
  const double spare = 1.0 / kDisplayHz - (glfwGetTime() - loopStart);
  if (spare > 0) std::this_thread::sleep_for(std::chrono::duration<double>(spare));
}

void makeParent(const std::string& path) {
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir);
}

void captureWindow(const std::string& path, int w, int h) {
  makeParent(path);
  std::vector<uint8_t> px(size_t(w) * size_t(h) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  Buffer img(w, h, 3);
  for (int y = 0; y < h; ++y)  // OpenGL's rows start at the bottom
    for (int x = 0; x < w; ++x) {
      const uint8_t* p = &px[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
      img.setRgb(x, y, Vec3(p[0], p[1], p[2]) / 255.0f);
    }
  writePng(path, img);
}

}  // namespace

void saveScreenshot(ViewerState& s, const std::string& path) {
  if (s.frame.output.data.empty()) return;
  makeParent(path);
  writePng(path, s.frame.output);
  s.message = "wrote " + path;
  std::printf("%s\n", s.message.c_str());
}

namespace {

// The window and its OpenGL 3.3 context with Dear ImGui on it; a clear error when there is no
// display to open it on.
GLFWwindow* openWindow(const ViewerOptions& o, const Scene& scene) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  glfwSetErrorCallback(onGlfwError);
  if ((!display || !*display) && (!wayland || !*wayland))
    throw InputError("tandem view", "display",
                     "no display to open a window on (DISPLAY and WAYLAND_DISPLAY are unset); "
                     "use `tandem render` to write images, or run under Xvfb "
                     "(xvfb-run tandem view ...)");
  if (!glfwInit())
    throw InputError("tandem view", "display",
                     "cannot open the display (" + glfwProblem +
                         "); use `tandem render` to write images instead");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GL_TRUE);
  GLFWwindow* window = glfwCreateWindow(o.render.width, o.render.height,
                                        ("Tandem: " + scene.name).c_str(), nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    throw InputError("tandem view", "OpenGL",
                     "cannot create an OpenGL 3.3 core window (" + glfwProblem +
                         "); use `tandem render` to write images instead");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);  // show frames as they come; the renderer sets the pace
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working folder
  installRedrawCallbacks(window);
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");

  return window;
}

// Where the mouse was, and whether the right button is looking around.
struct Pointer {
  double lastX = 0, lastY = 0;
  bool looking = false;
};

// Keys and mouse: WASD/QE fly the camera, the right button looks around, the middle one puts
// the fovea under the cursor, F12 saves a screenshot.
void handleInput(GLFWwindow* window, ViewerState& s, RenderWorker& worker, float dt, int eyes,
                 Pointer& ptr) {
  ImGuiIO& io = ImGui::GetIO();
  // Camera: WASD/QE to move (shift: 4x), right mouse button held to look around.
  if (!io.WantCaptureKeyboard) {
    auto down = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
    const float boost = down(GLFW_KEY_LEFT_SHIFT) > 0 ? 4.0f : 1.0f;
    const float r = down(GLFW_KEY_D) - down(GLFW_KEY_A), u = down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                f = down(GLFW_KEY_W) - down(GLFW_KEY_S);
    if (r != 0 || u != 0 || f != 0) s.playing = false, s.fly.move(r, u, f, dt * boost);
    static bool f12Was = false;
    const bool f12 = glfwGetKey(window, GLFW_KEY_F12) == GLFW_PRESS;
    if (f12 && !f12Was) saveScreenshot(s, s.screenshotFile);
    f12Was = f12;
  }
  double mx, my;
  glfwGetCursorPos(window, &mx, &my);
  const bool rmb = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  if (rmb && !io.WantCaptureMouse) {
    if (ptr.looking) s.fly.look(float(mx - ptr.lastX), float(my - ptr.lastY));
    ptr.looking = true;
    s.playing = false;
  } else {
    ptr.looking = false;
  }
  ptr.lastX = mx, ptr.lastY = my;

  // Gaze (Peres 2022): the middle mouse button held puts the fovea under the cursor, in whichever
  // eye it points at (the distribution is rebuilt only when the point moves).
  if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS && !io.WantCaptureMouse) {
    int ww = 1, wh = 1;
    glfwGetWindowSize(window, &ww, &wh);
    const double ex = mx / std::max(ww, 1) * eyes;
    const double gx = std::clamp(ex - std::floor(ex), 0.0, 1.0);
    const double gy = std::clamp(my / std::max(wh, 1), 0.0, 1.0);
    for (size_t i = 0; i < s.model.passes.size(); ++i) {
      auto& pm = s.model.passes[i];
      if (pm.type != "foveation") continue;
      if (pm.values["gaze"] != 1) worker.setParam(i, "gaze", pm.values["gaze"] = 1);
      if (pm.values["gaze_x"] != gx) worker.setParam(i, "gaze_x", pm.values["gaze_x"] = gx);
      if (pm.values["gaze_y"] != gy) worker.setParam(i, "gaze_y", pm.values["gaze_y"] = gy);
    }
  }
}

// Path playback and recording, in the scene-file path format (seconds).
void followPath(ViewerState& s, double now) {
  if (s.playing && s.path.size() >= 2) {
    const double t = now - s.playStart + s.path.front().time;
    if (t > s.path.back().time) s.playing = false;
    const CameraDesc c = sampleCameraPath(s.path, s.baseCamera, float(t));
    s.fly = FlyCamera::fromDesc(c);
  }
  if (s.recording && now - s.lastKey >= 0.25) {
    const CameraDesc c = s.fly.toDesc(s.baseCamera);
    s.path.push_back({float(now - s.recordStart), c.position, c.lookAt});
    s.lastKey = now;
  }
}

// The finished frame into the window's texture (reallocated when its size changed).
void upload(GLuint tex, const FinishedFrame& frame, int& texW, int& texH) {
  glBindTexture(GL_TEXTURE_2D, tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (frame.width != texW || frame.height != texH) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, frame.width, frame.height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, frame.rgba.data());
    texW = frame.width, texH = frame.height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, texW, texH, GL_RGBA, GL_UNSIGNED_BYTE,
                    frame.rgba.data());
  }
}

// Scripted runs: what the command line asked to write once enough frames have finished.
void writeScripted(const ViewerOptions& o, ViewerState& s, int fbw, int fbh) {
  if (!o.windowCapture.empty()) {
    captureWindow(o.windowCapture, fbw, fbh);
    std::printf("wrote %s\n", o.windowCapture.c_str());
  }
  if (!o.screenshot.empty()) saveScreenshot(s, o.screenshot);
}

void printReport(const ViewerState& s, const RenderWorker& worker) {
  std::printf(
      "view: %llu frames of %s at %dx%d; %.2f fps (mean frame %.2f ms over the last %zu); "
      "viewer cost (upload + UI) %.3f ms + present %.3f ms per displayed frame\n",
      static_cast<unsigned long long>(s.frame.serial), s.pipelineName.c_str(), s.frame.width,
      s.frame.height, s.history.framesPerSecond(), s.history.averageFrameMs(), s.history.size(),
      s.viewerFrames ? s.viewerMsSum / s.viewerFrames : 0.0,
      s.viewerFrames ? s.presentMsSum / s.viewerFrames : 0.0);
  std::printf("view: mean ms per pass:");
  for (const FrameHistory::PassRow& r : s.history.rows())
    std::printf(" %s %.2f", r.name.c_str(), r.averageMs);
  std::printf("\n");
  if (!worker.error().empty()) std::printf("view: %s\n", worker.error().c_str());
}

}  // namespace

int runViewer(const ViewerOptions& o) {
  validateRenderOptions(o.render);
  if (!(o.scale > 0.05f && o.scale <= 2.0f))
    throw InputError("command line", "--scale", "must be in (0.05, 2]");
  if (o.frames < 0) throw InputError("command line", "--frames", "must be >= 0");
  // Scene and pipeline first: bad input fails before any window appears.
  ViewerState s;
  s.opts = o;
  Scene scene = loadSceneToRender(o.render);
  s.scene = &scene;
  s.baseCamera = s.startCamera = cameraFor(scene, o.render);
  s.fly = FlyCamera::fromDesc(s.startCamera);
  s.fly.speed = std::max(0.1f, length(scene.bounds().extent()) * 0.15f);
  Pipeline pipeline = loadPipelineFor(o.render);
  s.pipelineName = o.render.pipeline;
  s.model = PipelineModel::from(pipeline, o.render.pipeline);
  // Progressive passes keep converging while the camera stands still.
  for (auto& p : s.model.passes)
    if (p.values.count("accumulate")) p.values["accumulate"] = 1, p.values["progress"] = 0;

  GLFWwindow* window = openWindow(o, scene);
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  ImageBlit blit;
  blit.init(tex);

  int fbw = 0, fbh = 0;
  glfwGetFramebufferSize(window, &fbw, &fbh);
  s.view.camera = s.fly.toDesc(s.baseCamera);
  s.view.stereo = stereoFor(scene, o.render);
  const int eyes = s.view.stereo.enabled ? 2 : 1;  // both eyes share the window side by side
  s.view.width = std::max(1, int(float(fbw) * o.scale) / eyes);
  s.view.height = std::max(1, int(float(fbh) * o.scale));
  RenderWorker worker(scene, s.model, s.view, o.render.seed,
                      renderSettingsFor(scene, o.render).gpu);

  double last = glfwGetTime();
  Pointer pointer;
  bool screenshotsDone = false, reportNow = false;
  int texW = 0, texH = 0;
  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    const double now = glfwGetTime();
    const float dt = float(std::min(now - last, 0.1));
    last = now;

    handleInput(window, s, worker, dt, eyes, pointer);

    followPath(s, now);

    glfwGetFramebufferSize(window, &fbw, &fbh);
    ViewState v = s.view;
    v.camera = s.fly.toDesc(s.baseCamera);
    v.width = std::max(1, int(float(fbw) * s.opts.scale) / eyes);
    v.height = std::max(1, int(float(fbh) * s.opts.scale));
    if (std::memcmp(&v.camera, &s.view.camera, sizeof(CameraDesc)) != 0 ||
        v.width != s.view.width || v.height != s.view.height ||
        v.shownBuffer != s.view.shownBuffer || v.varianceScale != s.view.varianceScale) {
      s.view = v;
      worker.setView(v);
    }

    // The viewer's own cost: upload + UI (+ drawing), timed every displayed frame.
    const auto t0 = Clock::now();
    const bool fresh = worker.takeFrame(s.frame);
    if (!fresh && redrawsPending == 0) {
      waitForNextRefresh(now);
      continue;
    }
    redrawsPending = std::max(0, redrawsPending - 1);
    if (fresh) {
      s.history.add(s.frame.timings);
      upload(tex, s.frame, texW, texH);
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (!o.hideUi) drawPanels(s, worker);
    ImGui::Render();
    glViewport(0, 0, fbw, fbh);
    if (texW > 0) {
      blit.draw(texW, texH, fbw, fbh);
    } else {
      glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
    }
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    s.viewerMs = float(msSince(t0));
    if (s.frame.serial > 0) s.viewerMsSum += s.viewerMs, ++s.viewerFrames;

    // Scripted runs: once enough frames have finished, write what was asked and maybe quit.
    if (!screenshotsDone && o.frames > 0 && s.frame.serial >= uint64_t(o.frames) &&
        s.frame.width == s.view.width * eyes && s.frame.height == s.view.height && texW > 0) {
      writeScripted(o, s, fbw, fbh);
      screenshotsDone = reportNow = true;
    }
    const auto t1 = Clock::now();
    glfwSwapBuffers(window);
    s.presentMs = float(msSince(t1));
    if (s.frame.serial > 0) s.presentMsSum += s.presentMs;
    if (reportNow) {  // after the swap, so the frame's present time is in the average
      reportNow = false;
      printReport(s, worker);
      if (o.exitAfter) glfwSetWindowShouldClose(window, GLFW_TRUE);
    }
    waitForNextRefresh(now);
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glDeleteTextures(1, &tex);
  glfwDestroyWindow(window);
  glfwTerminate();
  return 0;
}

}  // namespace tandem
