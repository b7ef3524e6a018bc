// The drawn objects' triangles numbered one after another (raster_args.h RasterSpan): drawn
// triangle i's object and its index over all objects' triangles. After scene.glsl.

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer SpansRef {
  RasterSpan s[];
};

uint spanTriangle(uint64_t spans, uint count, uint i, out int object) {
  SpansRef r = SpansRef(spans);
  int lo = 0, hi = int(count) - 1;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (r.s[mid].first <= i)
      lo = mid;
    else
      hi = mid - 1;
  }
  const RasterSpan span = r.s[lo];
  object = int(span.object);
  return Objects(S.objects).o[object].firstIndex / 3u + (i - span.first);
}
