// The compute rasterizer's per-pixel side, operation for operation Rasterizer::render's
// (raster/raster_tile.h): the same fixed-point edge functions and top-left rule, the same depth
// plane evaluated as the CPU evaluates it in its 64-pixel tiles (so depths agree to the bit where
// the set-up does), alpha masks tested along the pixel's camera ray. A pixel keeps the largest
// key, depth bits over the complement of the triangle's index (raster_args.h).
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Visibility { uint64_t v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer RasterArgsRef {
  RasterArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer RasterQueue {
  uint count, pad0, pad1, pad2;
  RasterTriangle t[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer RasterCounters { uint c[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer SampleInts { int v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer SampleUints {
  uint v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer SampleFloats {
  float v[];
};

const int kRasterTile = 64;  // the CPU's tile: its depth is evaluated from each tile's left edge

// Whether the centre of pixel (px, py) lies inside t (triangleBox's edge functions at one pixel).
bool coversPixel(RasterTriangle t, int px, int py) {
  const int64_t sx = (int64_t(px) << 8) + 128, sy = (int64_t(py) << 8) + 128;
  for (int e = 0; e < 3; ++e) {
    const int c = e == 2 ? 0 : e + 1;
    const int64_t dx = int64_t(t.x[c]) - t.x[e], dy = int64_t(t.y[c]) - t.y[e];
    const bool owns = dy < 0 || (dy == 0 && dx > 0);
    if (dx * (sy - t.y[e]) - dy * (sx - t.x[e]) + (owns ? 0 : -1) < 0) return false;
  }
  return true;
}

// The depth at pixel (px, py) as rowDepth and walkRowPixels compute it in the pixel's CPU tile.
float pixelDepth(RasterTriangle t, int px, int py) {
  const int x0 = max(px / kRasterTile * kRasterTile, t.px0);
  precise const float zRow =
      t.zRef + t.dzdy * (float(py) + 0.5 - t.yRef) + t.dzdx * (float(x0) + 0.5 - t.xRef);
  precise const float z = zRow + t.dzdx * float(px - x0);
  return z;
}

// Rasterizer::alphaKeeps: the texel under the pixel centre's camera ray passes the cutoff.
bool alphaKeeps(RasterTriangle t, GpuCamera cam, uint objectCount, int px, int py) {
  const int object = objectOfTriangle(t.triangle, objectCount);
  const GpuObject ob = Objects(S.objects).o[object];
  const int prim = int(t.triangle - ob.firstIndex / 3u);
  const uvec3 k = triangleVertices(ob, prim);
  vec3 o, d;
  float tnear, th, u, v;
  cameraRay(cam, px, py, o, d, tnear);
  intersectTriangle(o, d, vertexPositionAt(ob, k.x), vertexPositionAt(ob, k.y),
                    vertexPositionAt(ob, k.z), th, u, v);
  return surfaceAlpha(object, prim, u, v) >= Materials(S.materials).m[ob.material].alphaCutoff;
}

// Sample mode (Rasterizer::renderSamples): sample `id` at its fixed-point position, its depth from
// the plane at its position, the alpha mask along its camera ray.
void drawSample(RasterTriangle t, RasterArgs a, uint id) {
  SampleInts fixedPos = SampleInts(a.sampleFixed);
  const int64_t sx = fixedPos.v[2u * id], sy = fixedPos.v[2u * id + 1u];
  for (int e = 0; e < 3; ++e) {
    const int c = e == 2 ? 0 : e + 1;
    const int64_t dx = int64_t(t.x[c]) - t.x[e], dy = int64_t(t.y[c]) - t.y[e];
    const bool owns = dy < 0 || (dy == 0 && dx > 0);
    if (dx * (sy - t.y[e]) - dy * (sx - t.x[e]) + (owns ? 0 : -1) < 0) return;
  }
  SampleFloats pos = SampleFloats(a.samplePos);
  const vec2 p = vec2(pos.v[2u * id], pos.v[2u * id + 1u]);
  precise const float z = t.zRef + t.dzdx * (p.x - t.xRef) + t.dzdy * (p.y - t.yRef);
  if (!(z > 0.0 && z <= 1.0)) return;
  const uint64_t key = (uint64_t(floatBitsToUint(z)) << 32) | uint64_t(~t.triangle);
  Visibility vis = Visibility(a.visibility);
  if (vis.v[id] >= key) return;
  if (t.alphaMask != 0u) {
    const int object = objectOfTriangle(t.triangle, a.objectCount);
    const GpuObject ob = Objects(S.objects).o[object];
    const int prim = int(t.triangle - ob.firstIndex / 3u);
    const uvec3 k = triangleVertices(ob, prim);
    vec3 o, d;
    float tnear, th, u, v;
    cameraRayAt(a.camera, p, o, d, tnear);
    intersectTriangle(o, d, vertexPositionAt(ob, k.x), vertexPositionAt(ob, k.y),
                      vertexPositionAt(ob, k.z), th, u, v);
    if (surfaceAlpha(object, prim, u, v) < Materials(S.materials).m[ob.material].alphaCutoff)
      return;
  }
  atomicMax(vis.v[id], key);
}
// The samples of cell (cx, cy) (sample mode).
void drawCell(RasterTriangle t, RasterArgs a, int cx, int cy) {
  SampleUints start = SampleUints(a.sampleStart), ids = SampleUints(a.sampleIds);
  const uint c = uint(cy * a.cellsX + cx);
  for (uint k = start.v[c]; k < start.v[c + 1u]; ++k) drawSample(t, a, ids.v[k]);
}
// The cells a set-up triangle's box touches (sample mode): x0, y0, x1, y1.
ivec4 cellBox(RasterTriangle t, RasterArgs a) {
  return ivec4(t.px0 / a.cellW, t.py0 / a.cellH, min(a.cellsX - 1, t.px1 / a.cellW),
               min(a.cellsY - 1, t.py1 / a.cellH));
}

void drawPixel(RasterTriangle t, RasterArgs a, int px, int py) {
  if (!coversPixel(t, px, py)) return;
  const float z = pixelDepth(t, px, py);
  if (!(z > 0.0 && z <= 1.0)) return;
  const uint64_t key = (uint64_t(floatBitsToUint(z)) << 32) | uint64_t(~t.triangle);
  Visibility vis = Visibility(a.visibility);
  const uint i = uint(py) * uint(a.camera.width) + uint(px);
  if (vis.v[i] >= key) return;  // a plain read first: a hidden pixel needs no atomic
  if (t.alphaMask != 0u && !alphaKeeps(t, a.camera, a.objectCount, px, py)) return;
  atomicMax(vis.v[i], key);
}
