"""Foster 2015's hybrid motion blur from Python: post-process blur only, the hybrid (interleaved
samples where the blur cannot be right, a temporal sharp image elsewhere) and interleaved samples
everywhere, each timed and compared with distributed ray tracing of the same shading over the
same shutter (the Whitted shutter reference). `tandem experiment interleaved` is the full
version (error against N, colored-corner tiles, timing)."""
import argparse
import tandem

ap = argparse.ArgumentParser()
ap.add_argument("--width", type=int, default=960)
ap.add_argument("--height", type=int, default=540)
ap.add_argument("--frames", type=int, default=8)
ap.add_argument("--spp", type=int, default=256, help="reference samples per pixel")
args = ap.parse_args()

scene, shutter = "scenes/interleaved_motion.json", 0.1
truth = tandem.reference(scene, integrator="whitted", spp=args.spp, width=args.width,
                         height=args.height, shutter=shutter)["output"]
print("| pipeline | ms / frame | SSIM | RMSE |")
print("| --- | ---: | ---: | ---: |")
for pipeline, sets in [("postfx-motion-blur", {}), ("hybrid-motion-blur", {}),
                       ("interleaved-raster", {"interleaved_raster.mode": "motion_blur"})]:
    r = tandem.Renderer(scene, pipeline=pipeline, width=args.width, height=args.height,
                        shutter=shutter, sets=sets)
    out = r.render(frames=args.frames)
    m = tandem.compare(truth, out["output"])
    print(f"| {pipeline} | {r.timings()['frame']:.1f} | {m['ssim']:.4f} | {m['rmse']:.4f} |")
