#include "scene/scene_hash.h"

namespace tandem {

void hashCamera(Hasher& h, const CameraDesc& c) {
  h.pod(int(c.projection)).pod(c.position).pod(c.lookAt).pod(c.up).pod(c.vfovDeg);
  h.pod(c.orthoHeight).pod(c.nearPlane).pod(c.farPlane).pod(c.apertureDiameter);
  h.pod(c.focalLength).pod(c.focusDistance).pod(c.sensorWidth).pod(c.apertureBlades);
  h.pod(c.apertureRotationDeg);
}

void hashScene(Hasher& h, const Scene& s) {
  for (const Mesh& m : s.meshes)
    h.vec(m.positions).vec(m.normals).vec(m.tangents).vec(m.uvs).vec(m.indices);
  for (const Material& m : s.materials) {
    h.pod(m.emission).pod(m.ambient).pod(m.diffuse).pod(m.diffuseOpacity).pod(m.specular);
    h.pod(m.specularExponent).pod(m.reflectivity).pod(m.ior).pod(m.opacity).pod(m.tiling);
    h.pod(m.offset).pod(m.uvRotation).pod(m.castsShadows).pod(m.doubleSided);
    h.pod(int(m.alphaMode)).pod(m.alphaCutoff).pod(m.diffuseTexture).pod(m.emissionTexture);
    h.pod(m.specularTexture).pod(m.normalTexture).pod(m.normalScale);
    h.pod(m.metallicRoughnessTexture).pod(m.baseColor).pod(m.metallic).pod(m.roughness);
    // Hashed only when present, so cache keys of scenes without it stay as they were.
    if (m.occlusionTexture >= 0) h.pod(m.occlusionTexture).pod(m.occlusionStrength);
    const Vec3 tf = m.transmissionFilter;
    if (tf.x < 1.0f || tf.y < 1.0f || tf.z < 1.0f) h.pod(tf);
  }
  for (const Texture& t : s.textures)
    h.pod(t.texels.width)
        .pod(t.texels.height)
        .vec(t.texels.data)
        .pod(int(t.wrapS))
        .pod(int(t.wrapT));
  for (const Object& o : s.objects) {
    h.pod(o.mesh).pod(o.material).pod(o.parent).pod(o.local.position).pod(o.local.rotationDeg);
    h.pod(o.local.scale);
    for (const TransformKey& k : o.animation)
      h.pod(k.time).pod(k.transform.position).pod(k.transform.rotationDeg).pod(k.transform.scale);
  }
  for (const Light& l : s.lights) {
    h.pod(int(l.type)).pod(l.color).pod(l.intensity).pod(l.position).pod(l.direction);
    h.pod(l.attConstant).pod(l.attLinear).pod(l.attQuadratic).pod(l.range);
    h.pod(l.innerConeDeg).pod(l.outerConeDeg).pod(l.cosinePower).pod(l.castsShadows);
    h.pod(l.fromEmissiveMesh);
  }
  h.pod(s.ambient).pod(s.environmentIor).pod(s.skybox.color);
  for (int f : s.skybox.faces) h.pod(f);
  for (const CameraKey& k : s.cameraPath) h.pod(k.time).pod(k.position).pod(k.lookAt);
}

}  // namespace tandem
