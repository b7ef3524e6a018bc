#include "gpu/feature_scene.h"

#include <cmath>

#include "scene/primitives.h"

namespace tandem {

namespace {

// A texture of w x h texels from f(x, y) -> RGBA (linear).
template <class F>
Texture makeTexture(int w, int h, bool srgb, F&& f) {
  Texture t;
  t.name = "test";
  t.texels = Buffer(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec4 c = f(x, y);
      float* p = t.texels.at(x, y);
      p[0] = c.x, p[1] = c.y, p[2] = c.z, p[3] = c.w;
    }
  t.srgb = srgb;
  t.buildLevels();
  return t;
}

}  // namespace

Scene featureScene() {
  Scene s;
  s.name = "features";
  s.ambient = {0.05f, 0.05f, 0.06f};
  const int plane = s.addMesh(makePlane(2));
  const int sphere = s.addMesh(makeUvSphere(32, 16));
  const int cube = s.addMesh(makeCube());
  // Non-power-of-two sizes (the wrap's division path) and power-of-two ones.
  Texture checker = checkerTexture(96, 6, {0.9f, 0.8f, 0.6f}, {0.2f, 0.25f, 0.3f});
  checker.wrapS = WrapMode::MirroredRepeat;
  checker.wrapT = WrapMode::ClampToEdge;
  const int checkerTex = s.addTexture(checker);
  const int holes = s.addTexture(makeTexture(64, 64, true, [](int x, int y) {
    const bool hole = ((x / 8) + (y / 8)) % 3 == 0;
    return Vec4(0.3f + 0.01f * float(x), 0.6f, 0.2f + 0.01f * float(y), hole ? 0.0f : 1.0f);
  }));
  const int bumps = s.addTexture(makeTexture(64, 32, false, [](int x, int y) {
    const float a = std::sin(float(x) * 0.5f) * 0.4f, b = std::cos(float(y) * 0.7f) * 0.4f;
    return Vec4(0.5f + 0.5f * a, 0.5f + 0.5f * b, 0.9f, 1.0f);
  }));
  const int metalRough = s.addTexture(makeTexture(32, 32, false, [](int x, int y) {
    return Vec4(1.0f, float(y) / 31.0f, float(x) / 31.0f, 1.0f);
  }));
  const int glow = s.addTexture(makeTexture(
      16, 16, true, [](int x, int) { return Vec4(x % 4 == 0 ? 1.0f : 0.0f, 0.5f, 0.1f, 1.0f); }));

  Material floor;
  floor.name = "floor";
  floor.diffuseTexture = checkerTex;
  floor.tiling = {3, 2};
  floor.offset = {0.1f, -0.2f};
  floor.uvRotation = 0.4f;
  floor.specular = {0.3f, 0.3f, 0.3f};
  floor.specularExponent = 60;
  floor.reflectivity = 0.2f;
  floor.occlusionTexture = metalRough;
  floor.occlusionStrength = 0.7f;
  s.addObject("floor", plane, s.addMaterial(floor), {{0, 0, 0}, {0, 0, 0}, {6, 1, 6}});

  Material masked;
  masked.name = "masked";
  masked.diffuseTexture = holes;
  masked.alphaMode = AlphaMode::Mask;
  masked.doubleSided = true;
  s.addObject("screen", plane, s.addMaterial(masked), {{-1.5f, 1.2f, -1}, {80, 20, 0}, {1, 1, 1}});

  Material bumpy;
  bumpy.name = "bumpy";
  bumpy.baseColor = {0.8f, 0.5f, 0.3f};
  bumpy.metallic = 0.8f;
  bumpy.roughness = 0.6f;
  bumpy.metallicRoughnessTexture = metalRough;
  bumpy.diffuseTexture = checkerTex;
  bumpy.normalTexture = bumps;
  bumpy.normalScale = 0.8f;
  bumpy.emissionTexture = glow;
  bumpy.emission = {0.2f, 0.2f, 0.2f};
  bumpy.specularTexture = glow;
  s.addObject("bumpy", sphere, s.addMaterial(bumpy),
              {{0.8f, 0.8f, -0.5f}, {0, 30, 0}, {0.8f, 0.8f, 0.8f}});

  Material glass;
  glass.name = "tinted glass";
  glass.diffuse = {0.1f, 0.1f, 0.1f};
  glass.opacity = 0.2f;
  glass.reflectivity = 0.1f;
  glass.ior = 1.4f;
  glass.transmissionFilter = {0.9f, 0.6f, 0.4f};
  glass.specular = {0.5f, 0.5f, 0.5f};
  glass.specularExponent = 120;
  s.addObject("glass", sphere, s.addMaterial(glass),
              {{-0.6f, 0.6f, 0.8f}, {0, 0, 0}, {0.6f, 0.6f, 0.6f}});

  Material blended;
  blended.name = "blended";
  blended.diffuseTexture = holes;
  blended.alphaMode = AlphaMode::Blend;
  blended.castsShadows = true;
  s.addObject("box", cube, s.addMaterial(blended),
              {{1.8f, 0.52f, 1.2f}, {0, 40, 0}, {0.4f, 0.5f, 0.4f}});

  Material ghost;  // casts no shadow
  ghost.name = "ghost";
  ghost.diffuse = {0.2f, 0.7f, 0.9f};
  ghost.castsShadows = false;
  const int ghostObject = s.addObject("ghost", cube, s.addMaterial(ghost),
                                      {{0, 2.6f, 0}, {20, 0, 10}, {0.3f, 0.1f, 0.3f}});
  // It turns and slides (motion vectors of a moving object).
  s.objects[size_t(ghostObject)].animation = {{0.0f, {{0, 0, 0}, {0, 0, 0}, {1, 1, 1}}},
                                              {1.0f, {{0.6f, -0.3f, 0.2f}, {0, 50, 0}, {1, 1, 1}}}};

  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3{0.4f, -1.0f, -0.3f});
  sun.intensity = 2.0f;
  s.lights.push_back(sun);
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {-2, 3.5f, 2};
  spot.direction = normalize(Vec3{0.5f, -1.0f, -0.5f});
  spot.innerConeDeg = 15;
  spot.outerConeDeg = 35;
  spot.cosinePower = 1.0f;
  spot.intensity = 30;
  spot.color = {1.0f, 0.8f, 0.6f};
  s.lights.push_back(spot);
  Light bulb;
  bulb.position = {1.5f, 1.5f, 2.0f};
  bulb.intensity = 4;
  bulb.range = 4;
  bulb.attConstant = 0.5f;
  bulb.attLinear = 0.2f;
  s.lights.push_back(bulb);
  Light dark;  // no shadows: lit everywhere it reaches
  dark.position = {0, 0.3f, 2.5f};
  dark.intensity = 0.5f;
  dark.castsShadows = false;
  s.lights.push_back(dark);

  // A cube-map sky of six flat faces, each its own colour.
  for (int f = 0; f < 6; ++f)
    s.skybox.faces[f] = s.addTexture(makeTexture(4, 4, true, [f](int x, int y) {
      return Vec4(0.1f * float(f + 1), 0.05f * float(x + 1), 0.08f * float(y + 1), 1.0f);
    }));
  return s;
}

CameraDesc featureCamera() {
  CameraDesc c;
  c.position = {0.5f, 2.2f, 4.5f};
  c.lookAt = {0, 0.6f, 0};
  c.vfovDeg = 55;
  return c;
}

}  // namespace tandem
