// The camera a sample of a (time, lens) pair sees through: shared by the passes that sample the
// shutter and the lens with one camera per pair (interleaved sampling, the accumulation
// baselines).
#pragma once
#include "raster/sample_tiles.h"
#include "scene/camera.h"

namespace tandem {

struct View;

// The camera of view `v` at pair p: along its shutter path at p.tau (if `time`), moved to the
// lens point (u1, u2) (if `lens`) with the projection sheared, plus a sub-pixel jitter.
Camera cameraForPair(const View& v, const TimeLensPair& p, bool time, bool lens, Vec2 jitter);

}  // namespace tandem
