// The scene on the GPU: every object's world-space triangles with a BVH of their own, and one BVH
// over the objects (two levels, so an object that moves is rebuilt alone and per-object
// selections can skip whole objects), in device buffers that kernels reach by address; and what
// shading needs (shaders/scene_data.h): vertex attributes, materials, textures with their mip
// chains, lights and the sky, reached from one SceneArgs record.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "gpu/gpu_commands.h"
#include "gpu/gpu_memory.h"
#include "gpu/shaders/bvh.h"
#include "gpu/shaders/scene_data.h"
#include "scene/frame_scene.h"

namespace tandem {

class GpuScene {
 public:
  explicit GpuScene(GpuMemory& memory) : memory_(memory) {}
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Brings the device copy up to `fs` (geometryVersion): objects whose triangles moved have
  // their BVH refitted (built on first sight), the BVH over the objects is rebuilt, and
  // everything is uploaded through `cmd` (submitted and waited for).
  void update(const FrameScene& fs, GpuCommands& cmd);
  // Whether the device copy is `fs` already (update would do nothing).
  bool current(const FrameScene& fs) const {
    return fs.geometryVersion == version_ && fs.scene == scene_ &&
           fs.objects.size() == objects_.size();
  }
  // The scene's contents changed in place (lights, materials): the next update uploads all.
  void invalidate() { scene_ = nullptr; }
  // The trace arguments for this scene (rays, hits and count left for the caller).
  TraceArgs traceArgs() const;
  // The device address of the scene's SceneArgs record.
  uint64_t sceneAddress() const { return args_.address; }
  size_t triangles() const { return triangleCount_; }
  uint64_t deviceBytes() const;

 private:
  struct ObjectBvh {
    std::vector<BvhNode> nodes;
    std::vector<float> triangles;  // 9 floats each, in leaf order
    std::vector<uint32_t> prims;   // each triangle's index in the object
    // Moving while the shutter is open: `steps` time steps of each triangle (9 floats a step,
    // a triangle's steps together, in leaf order); the boxes bound every step.
    uint32_t steps = 0;
    std::vector<float> stepTriangles;
    Bounds3 bounds;
  };
  static ObjectBvh buildObject(const Scene& scene, const FrameObject& o, size_t index);
  static void refitObject(ObjectBvh& ob, const Scene& scene, const FrameObject& o, size_t index);
  // What goes to the device in one submission: each piece copied through the staging buffer
  // into its own device buffer.
  struct Staging {
    struct Piece {
      GpuBuffer* dst;
      std::vector<char> bytes;
    };
    std::vector<Piece> pieces;
  };
  // Adds a piece, growing `dst` to hold it first (so its address is final once staged).
  template <class T>
  void stage(Staging& st, GpuBuffer& dst, const T* data, size_t bytes) {
    ensure(dst, std::max<size_t>(bytes, 16));
    const char* p = reinterpret_cast<const char*>(data);
    st.pieces.push_back({&dst, std::vector<char>(p, p + bytes)});
  }
  void record(const Staging& st, GpuCommands& cmd);
  void upload(GpuCommands& cmd, bool sceneChanged, const FrameScene& fs);
  // The shading data (materials, textures, lights, sky: when the scene changed; vertices: every
  // update) and the SceneArgs record.
  void stageShading(Staging& st, bool sceneChanged, const FrameScene& fs);
  GpuBuffer& ensure(GpuBuffer& b, size_t bytes);

  GpuMemory& memory_;
  uint64_t version_ = ~0ull;
  const Scene* scene_ = nullptr;
  std::vector<ObjectBvh> objects_;
  // Each object's positions, then those of its time steps, when its BVH was built.
  std::vector<std::vector<Vec3>> built_;
  GpuBuffer nodes_, triangles_, prims_, roots_, motion_, motionTriangles_, staging_;
  // Shading data: per scene, and per update (vertices).
  GpuBuffer materials_, textures_, levels_, texels_, lights_, decode_, objectsBuf_;
  GpuBuffer positions_, normals_, tangents_, uvs_, indices_, stepPositions_, stepNormals_, args_;
  SceneArgs sceneArgs_{};
  uint32_t topRoot_ = 0;
  size_t triangleCount_ = 0;
};

}  // namespace tandem
