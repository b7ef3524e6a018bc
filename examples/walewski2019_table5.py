"""Walewski et al. 2019, Table 5 from Python: per static shot, the raster stage (RAST), the heuristic (HEUR),
the ray-traced stage (RAYT) and the whole frame of hybrid-heuristic, against the frame of
rt-only (Whitted ray tracing of everything, the same shading), with SSIM against rt-only.
`tandem experiment heuristic` is the full version (four scenes, 1280x720, camera paths)."""
import argparse
import tandem

ap = argparse.ArgumentParser()
ap.add_argument("--width", type=int, default=1280)
ap.add_argument("--height", type=int, default=720)
ap.add_argument("--frames", type=int, default=5, help="timed frames (median) after one warm-up")
args = ap.parse_args()


def median_passes(r, frames):
    r.render()  # warm-up: BVH, probes, shadow maps
    runs = []
    for _ in range(frames):
        out = r.render()
        runs.append(r.timings())
    mid = sorted(runs, key=lambda t: t["frame"])[len(runs) // 2]
    return mid, out


print("| scene | RAST ms | HEUR ms | RAYT ms | FRAME ms | RAYT ONLY FRAME ms | FRAME / RAYT ONLY | SSIM |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for scene in ["spheres", "scenes/atrium_spheres.json", "scenes/atrium_statue.json",
              "scenes/cornell_spheres.json"]:
    hybrid = tandem.Renderer(scene, pipeline="hybrid-heuristic", width=args.width, height=args.height)
    rt = tandem.Renderer(scene, pipeline="rt-only", width=args.width, height=args.height)
    h, h_out = median_passes(hybrid, args.frames)
    t, t_out = median_passes(rt, args.frames)
    p = h["passes"]
    rast = p.get("raster_gbuffer", 0) + p.get("deferred_shading", 0)
    ssim = tandem.compare(t_out["output"], h_out["output"])["ssim"]
    print(f"| {scene} | {rast:.1f} | {p['heuristic']:.2f} | {p['rt_secondary']:.1f} | "
          f"{h['frame']:.1f} | {t['frame']:.1f} | {h['frame'] / t['frame']:.2f} | {ssim:.4f} |")
