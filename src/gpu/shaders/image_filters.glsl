// What the image-space kernels share with core/image_filters.cpp: the median of nine values by
// the same 19 compare-exchanges (median9).
void order(inout float a, inout float b) {
  const float lo = min(a, b), hi = max(a, b);
  a = lo;
  b = hi;
}
float median9(float q[9]) {
  order(q[1], q[2]); order(q[4], q[5]); order(q[7], q[8]);
  order(q[0], q[1]); order(q[3], q[4]); order(q[6], q[7]);
  order(q[1], q[2]); order(q[4], q[5]); order(q[7], q[8]);
  order(q[0], q[3]); order(q[5], q[8]); order(q[4], q[7]);
  order(q[3], q[6]); order(q[1], q[4]); order(q[2], q[5]);
  order(q[4], q[7]); order(q[4], q[2]); order(q[6], q[4]);
  order(q[4], q[2]);
  return q[4];
}
