// What GPU passes of the G-buffer take (shaders/gbuffer_args.h): its targets' device addresses
// for a writer or a reader, a view's cameras, and the objects' motion since last frame.
#pragma once
#include "gpu/shaders/gbuffer_args.h"
#include "pipeline/frame_context.h"
#include "pipeline/pass.h"

namespace tandem {

// The G-buffer targets `pass` writes, on the device (depth and motion 0 unless something reads
// them, as gbufferTargets), recorded in this submission's constants; its address.
uint64_t gbufferDeviceTargets(FrameContext& ctx, const Pass& pass);
// The same with only the targets something reads (the rest 0): vbuffer_shading's.
uint64_t gbufferDeviceTargetsIfConsumed(FrameContext& ctx, const Pass& pass);
// The targets `pass` reads (gbufferSampleSlots; depth and motion 0), likewise.
uint64_t gbufferDeviceSources(FrameContext& ctx, const Pass& pass);
// View v of the frame as kernels take it; its address in this submission's constants.
uint64_t gpuViewConstants(FrameContext& ctx, const View& v);
// Every object's motion since last frame (GpuObjectMotion), likewise.
uint64_t gpuObjectMotionConstants(FrameContext& ctx);

}  // namespace tandem
