#include "scene/builtin_scenes.h"

#include "core/error.h"
#include "scene/primitives.h"

namespace tandem {

const std::vector<std::string>& builtinSceneNames() {
  static const std::vector<std::string> names = {"cornell", "spheres", "atrium"};
  return names;
}

bool isBuiltinScene(const std::string& name) {
  for (const auto& n : builtinSceneNames())
    if (n == name) return true;
  return false;
}

Scene makeBuiltinScene(const std::string& name) {
  if (name == "cornell") return makeCornellScene();
  if (name == "spheres") return makeSpheresScene();
  if (name == "atrium") return makeAtriumScene();
  throw InputError(name, "scene", "not a file and not a built-in scene (cornell, spheres, atrium)");
}

namespace {

Material diffuseMaterial(const char* name, Vec3 albedo) {
  Material m;
  m.name = name;
  m.diffuse = albedo;
  m.ambient = albedo;
  return m;
}

Material mirrorMaterial(const char* name) {
  Material m;
  m.name = name;
  m.diffuse = {0.02f, 0.02f, 0.02f};
  m.ambient = m.diffuse;
  m.specular = {0.9f, 0.9f, 0.9f};
  m.specularExponent = 255;
  m.reflectivity = 1.0f;
  return m;
}

Material glassMaterial(const char* name, float ior) {
  Material m;
  m.name = name;
  m.diffuse = {0.02f, 0.02f, 0.02f};
  m.ambient = m.diffuse;
  m.specular = {0.6f, 0.6f, 0.6f};
  m.specularExponent = 200;
  m.reflectivity = 0.05f;
  m.ior = ior;
  m.opacity = 0.0f;
  return m;
}

Transform xform(Vec3 p, Vec3 rot = {0, 0, 0}, Vec3 s = {1, 1, 1}) {
  return {p, rot, s};
}

}  // namespace

Scene makeCornellScene() {
  Scene s;
  s.name = "cornell";
  int plane = s.addMesh(makePlane(1));
  int cube = s.addMesh(makeCube());
  int sphere = s.addMesh(makeUvSphere(64, 32));
  int white = s.addMaterial(diffuseMaterial("white", {0.73f, 0.73f, 0.73f}));
  int red = s.addMaterial(diffuseMaterial("red", {0.63f, 0.065f, 0.05f}));
  int green = s.addMaterial(diffuseMaterial("green", {0.14f, 0.45f, 0.091f}));
  int mirror = s.addMaterial(mirrorMaterial("mirror"));
  int glass = s.addMaterial(glassMaterial("glass", 1.5f));
  Material lightMat = diffuseMaterial("light", {0.78f, 0.78f, 0.78f});
  lightMat.emission = {17, 12, 4};  // the Cornell box data's Ke
  lightMat.castsShadows = false;
  int light = s.addMaterial(lightMat);

  s.addObject("floor", plane, white, xform({0, 0, 0}));
  s.addObject("ceiling", plane, white, xform({0, 2, 0}, {180, 0, 0}));
  s.addObject("back", plane, white, xform({0, 1, -1}, {90, 0, 0}));
  s.addObject("left", plane, red, xform({-1, 1, 0}, {0, 0, -90}));
  s.addObject("right", plane, green, xform({1, 1, 0}, {0, 0, 90}));
  s.addObject("light", plane, light, xform({0, 1.98f, 0}, {180, 0, 0}, {0.235f, 1, 0.19f}));
  s.addObject("tallBox", cube, white,
              xform({-0.35f, 0.6f, -0.35f}, {0, 18, 0}, {0.3f, 0.6f, 0.3f}));
  s.addObject("mirrorSphere", sphere, mirror,
              xform({0.45f, 0.35f, -0.35f}, {}, {0.35f, 0.35f, 0.35f}));
  s.addObject("glassSphere", sphere, glass, xform({0.0f, 0.3f, 0.45f}, {}, {0.3f, 0.3f, 0.3f}));
  s.ambient = {0.03f, 0.03f, 0.03f};
  s.skybox.color = {0, 0, 0};
  s.camera.position = {0, 1, 3.9f};
  s.camera.lookAt = {0, 1, 0};
  s.camera.vfovDeg = 39.3f;
  s.camera.focusDistance = 3.9f;
  s.hasCamera = true;
  s.cameraPath = {{0, {-0.5f, 1.1f, 3.9f}, {0, 0.9f, 0}}, {4, {0.5f, 0.9f, 3.9f}, {0, 0.9f, 0}}};
  return s;
}

Scene makeSpheresScene() {
  Scene s;
  s.name = "spheres";
  int plane = s.addMesh(makePlane(4));
  int sphere = s.addMesh(makeUvSphere(48, 24));
  int floorTex = s.addTexture(checkerTexture(512, 16, {0.8f, 0.8f, 0.8f}, {0.15f, 0.15f, 0.18f}));
  int wallTex = s.addTexture(checkerTexture(256, 8, {0.7f, 0.55f, 0.4f}, {0.45f, 0.3f, 0.2f}));
  Material floorMat = diffuseMaterial("floor", {1, 1, 1});
  floorMat.diffuseTexture = floorTex;
  floorMat.tiling = {4, 4};
  floorMat.specular = {0.2f, 0.2f, 0.2f};
  floorMat.specularExponent = 40;
  floorMat.reflectivity = 0.15f;
  int floorM = s.addMaterial(floorMat);
  Material wallMat = diffuseMaterial("wall", {1, 1, 1});
  wallMat.diffuseTexture = wallTex;
  wallMat.tiling = {3, 2};
  int wallM = s.addMaterial(wallMat);
  s.addObject("floor", plane, floorM, xform({0, 0, 0}, {}, {10, 1, 10}));
  s.addObject("backWall", plane, wallM, xform({0, 4, -10}, {90, 0, 0}, {10, 1, 4}));
  s.addObject("leftWall", plane, wallM, xform({-10, 4, 0}, {0, 0, -90}, {4, 1, 10}));
  s.addObject("rightWall", plane, wallM, xform({10, 4, 0}, {0, 0, 90}, {4, 1, 10}));
  // A 5 x 5 grid alternating mirror, glass and coloured glossy spheres.
  const Vec3 colours[5] = {{0.8f, 0.2f, 0.2f},
                           {0.2f, 0.7f, 0.3f},
                           {0.2f, 0.3f, 0.8f},
                           {0.8f, 0.7f, 0.2f},
                           {0.7f, 0.3f, 0.7f}};
  int mirror = s.addMaterial(mirrorMaterial("mirror"));
  int glass = s.addMaterial(glassMaterial("glass", 1.5f));
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      int kind = (i + 2 * j) % 3, mat;
      if (kind == 0) {
        mat = mirror;
      } else if (kind == 1) {
        mat = glass;
      } else {
        Material m = diffuseMaterial("glossy", colours[(i + j) % 5]);
        m.specular = {0.5f, 0.5f, 0.5f};
        m.specularExponent = 80;
        m.reflectivity = 0.2f;
        mat = s.addMaterial(m);
      }
      std::string name = "sphere" + std::to_string(j * 5 + i);
      int obj = s.addObject(name, sphere, mat, xform({-6.0f + 3.0f * i, 1.0f, -6.0f + 3.0f * j}));
      // Walewski et al. 2019 §4: reflective and refractive objects are set as relevant.
      if (kind < 2) s.objects[size_t(obj)].heuristic.K = 4;
    }
  // The middle sphere bobs up and down so motion vectors have something to show.
  Object& bob = s.objects[s.objects.size() - 13];
  Transform rest = bob.local, up = rest;
  up.position += Vec3(0, 1.5f, 0);
  bob.animation = {{0, rest}, {2, up}, {4, rest}};
  bob.local = {};
  Light sun;
  sun.type = LightType::Directional;
  sun.name = "sun";
  sun.direction = normalize(Vec3(-0.4f, -1.0f, -0.5f));
  sun.intensity = 2.5f;
  sun.color = {1.0f, 0.95f, 0.85f};
  s.lights.push_back(sun);
  for (int k = 0; k < 2; ++k) {
    Light p;
    p.type = LightType::Point;
    p.name = "point" + std::to_string(k);
    p.position = {k ? 5.0f : -5.0f, 6.0f, 4.0f};
    p.intensity = 40.0f;
    p.color = k ? Vec3(0.6f, 0.7f, 1.0f) : Vec3(1.0f, 0.8f, 0.6f);
    s.lights.push_back(p);
  }
  s.ambient = {0.05f, 0.05f, 0.06f};
  s.skybox.color = {0.35f, 0.5f, 0.75f};
  s.camera.position = {0, 6, 14};
  s.camera.lookAt = {0, 1, 0};
  s.camera.vfovDeg = 50;
  s.camera.focusDistance = 14;
  s.hasCamera = true;
  s.cameraPath = {
      {0, {-8, 5, 13}, {0, 1, 0}}, {5, {0, 7, 15}, {0, 1, 0}}, {10, {8, 5, 13}, {0, 1, 0}}};
  return s;
}

namespace {

// The atrium's sun, four warm lamps under the colonnades, a spot over the courtyard, the sky, and
// its camera and path.
void lightAtrium(Scene& s) {
  Light sun;
  sun.type = LightType::Directional;
  sun.name = "sun";
  sun.direction = normalize(Vec3(-0.3f, -1.0f, -0.4f));
  sun.intensity = 3.0f;
  sun.color = {1.0f, 0.93f, 0.8f};
  s.lights.push_back(sun);
  const Vec3 lampPos[4] = {{-8, 3, -5}, {8, 3, -5}, {-8, 3, 5}, {8, 3, 5}};
  for (int k = 0; k < 4; ++k) {
    Light p;
    p.type = LightType::Point;
    p.name = "lamp" + std::to_string(k);
    p.position = lampPos[k];
    p.intensity = 15.0f;
    p.color = {1.0f, 0.7f, 0.4f};
    s.lights.push_back(p);
  }
  Light spot;
  spot.type = LightType::Spot;
  spot.name = "spot";
  spot.position = {0, 9, 0};
  spot.direction = {0, -1, 0};
  spot.intensity = 120.0f;
  spot.innerConeDeg = 15;
  spot.outerConeDeg = 25;
  s.lights.push_back(spot);
  s.ambient = {0.08f, 0.08f, 0.1f};
  s.skybox.color = {0.45f, 0.6f, 0.85f};
  s.camera.position = {-11, 2.2f, 9};
  s.camera.lookAt = {4, 2.5f, -3};
  s.camera.vfovDeg = 60;
  s.camera.focusDistance = 10;
  s.hasCamera = true;
  s.cameraPath = {{0, {-11, 2.2f, 9}, {4, 2.5f, -3}},
                  {5, {0, 3.0f, 8}, {0, 2.5f, -6}},
                  {10, {11, 2.2f, 9}, {-4, 2.5f, -3}}};
}

}  // namespace

Scene makeAtriumScene() {
  // A two-storey colonnaded courtyard in the spirit of Crytek Sponza: tessellated columns with
  // capitals, arches between them, balcony slabs, a tiled floor, outer walls and hanging cloth.
  Scene s;
  s.name = "atrium";
  int plane = s.addMesh(makePlane(64));
  int cube = s.addMesh(makeCube());
  int column = s.addMesh(makeCylinder(48, 16, false));
  int capital = s.addMesh(makeCylinder(48, 3, true));
  int arch = s.addMesh(makeArch(0.7f, 1.0f, 0.6f, 32));
  int cloth = s.addMesh(makeCloth(1.6f, 3.2f, 40, 60, 0.25f, 3));
  int urn = s.addMesh(makeUvSphere(64, 32));
  int tiles = s.addTexture(checkerTexture(512, 32, {0.62f, 0.58f, 0.5f}, {0.35f, 0.3f, 0.26f}));
  Material floorMat = diffuseMaterial("tiles", {1, 1, 1});
  floorMat.diffuseTexture = tiles;
  floorMat.tiling = {6, 4};
  floorMat.specular = {0.15f, 0.15f, 0.15f};
  floorMat.specularExponent = 30;
  int floorM = s.addMaterial(floorMat);
  Material stone = diffuseMaterial("stone", {0.7f, 0.65f, 0.55f});
  stone.specular = {0.05f, 0.05f, 0.05f};
  stone.specularExponent = 10;
  int stoneM = s.addMaterial(stone);
  int wallM = s.addMaterial(diffuseMaterial("plaster", {0.75f, 0.7f, 0.6f}));
  const Vec3 clothColours[3] = {{0.6f, 0.1f, 0.1f}, {0.1f, 0.35f, 0.15f}, {0.15f, 0.2f, 0.55f}};
  int clothM[3];
  for (int k = 0; k < 3; ++k) {
    Material c = diffuseMaterial("cloth", clothColours[k]);
    c.doubleSided = true;
    clothM[k] = s.addMaterial(c);
  }
  Material bronze = diffuseMaterial("bronze", {0.3f, 0.2f, 0.1f});
  bronze.specular = {0.8f, 0.6f, 0.4f};
  bronze.specularExponent = 120;
  bronze.reflectivity = 0.5f;
  int bronzeM = s.addMaterial(bronze);

  const float hx = 12, hz = 7;  // courtyard half extents (columns stand on this rectangle)
  const float storey[2] = {0.0f, 4.6f}, colHeight[2] = {4.0f, 3.4f};
  s.addObject("floor", plane, floorM, xform({0, 0, 0}, {}, {hx + 3, 1, hz + 3}));
  s.addObject("wallBack", plane, wallM, xform({0, 4.5f, -(hz + 3)}, {90, 0, 0}, {hx + 3, 1, 4.5f}));
  s.addObject("wallFront", plane, wallM, xform({0, 4.5f, hz + 3}, {-90, 0, 0}, {hx + 3, 1, 4.5f}));
  s.addObject("wallLeft", plane, wallM,
              xform({-(hx + 3), 4.5f, 0}, {0, 0, -90}, {4.5f, 1, hz + 3}));
  s.addObject("wallRight", plane, wallM, xform({hx + 3, 4.5f, 0}, {0, 0, 90}, {4.5f, 1, hz + 3}));
  int n = 0;
  for (int level = 0; level < 2; ++level) {
    float y0 = storey[level], h = colHeight[level];
    // Columns along the long sides (z = +-hz) and short sides (x = +-hx), 2 m apart.
    std::vector<std::pair<Vec3, float>> spots;  // column base, arch rotation about Y
    for (int i = 0; i <= 12; ++i) {
      float x = -hx + 2.0f * i;
      spots.push_back({{x, y0, -hz}, 0});
      spots.push_back({{x, y0, hz}, 0});
    }
    for (int i = 1; i < 7; ++i) {
      float z = -hz + 2.0f * i;
      spots.push_back({{-hx, y0, z}, 90});
      spots.push_back({{hx, y0, z}, 90});
    }
    for (auto& [p, rot] : spots) {
      std::string id = std::to_string(n++);
      s.addObject("column" + id, column, stoneM, xform(p, {}, {0.25f, h, 0.25f}));
      s.addObject("capital" + id, capital, stoneM,
                  xform(p + Vec3(0, h - 0.25f, 0), {}, {0.38f, 0.25f, 0.38f}));
      s.addObject("base" + id, cube, stoneM,
                  xform(p + Vec3(0, 0.12f, 0), {}, {0.36f, 0.12f, 0.36f}));
      // An arch spanning to the next column along the side.
      bool lastX = rot == 0 && p.x >= hx - 0.01f;
      bool lastZ = rot == 90 && p.z >= hz - 2.01f;
      if (!lastX && !lastZ) {
        Vec3 mid = rot == 0 ? p + Vec3(1, h - 0.85f, 0) : p + Vec3(0, h - 0.85f, 1);
        s.addObject("arch" + id, arch, stoneM, xform(mid, {0, rot, 0}, {1, 0.85f, 1}));
      }
    }
    // Balcony slabs over each colonnade.
    float ys = y0 + h + 0.3f;
    s.addObject("slabN" + std::to_string(level), cube, stoneM,
                xform({0, ys, -hz - 1.2f}, {}, {hx + 1.5f, 0.3f, 1.6f}));
    s.addObject("slabS" + std::to_string(level), cube, stoneM,
                xform({0, ys, hz + 1.2f}, {}, {hx + 1.5f, 0.3f, 1.6f}));
    s.addObject("slabW" + std::to_string(level), cube, stoneM,
                xform({-hx - 1.2f, ys, 0}, {}, {1.6f, 0.3f, hz - 0.4f}));
    s.addObject("slabE" + std::to_string(level), cube, stoneM,
                xform({hx + 1.2f, ys, 0}, {}, {1.6f, 0.3f, hz - 0.4f}));
  }
  // Hanging cloth under the upper arches of both long sides.
  for (int i = 0; i < 12; ++i) {
    float x = -hx + 1.0f + 2.0f * i;
    float z = (i % 2) ? -hz : hz;
    s.addObject("cloth" + std::to_string(i), cloth, clothM[i % 3], xform({x, 7.6f, z}, {0, 0, 0}));
  }
  // Bronze urns in the courtyard.
  for (int i = 0; i < 4; ++i) {
    Vec3 p{-6.0f + 4.0f * i, 0.8f, (i % 2) ? 2.0f : -2.0f};
    s.addObject("urn" + std::to_string(i), urn, bronzeM, xform(p, {}, {0.8f, 0.8f, 0.8f}));
  }
  lightAtrium(s);
  return s;
}

}  // namespace tandem
