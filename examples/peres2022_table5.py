"""Peres 2022, the quality table from Python: Base (full screen, 4 spp, A-Trous), NH3LD (three
foveation layers, non-homogeneous A-Trous) and NH3LD with the periphery accumulated over frames,
both eyes of the Pink Room, against the same path tracer converged (diffuse-gi reference), with
frame times. `tandem experiment foveated` is the full version (three scenes, fhd and quest2)."""
import argparse
import tandem

ap = argparse.ArgumentParser()
ap.add_argument("--width", type=int, default=480, help="one eye")
ap.add_argument("--height", type=int, default=540)
ap.add_argument("--frames", type=int, default=8)
ap.add_argument("--spp", type=int, default=1024, help="reference samples per pixel")
args = ap.parse_args()

scene = "scenes/foveated_pink_room.json"
truth = tandem.reference(scene, integrator="diffuse-gi", spp=args.spp, width=args.width,
                         height=args.height, stereo=True)["output"]
print("| configuration | ms / frame | SSIM | PSNR dB |")
print("| --- | ---: | ---: | ---: |")
for name, pipeline, sets in [("Base", "foveated-base", {}), ("NH3LD", "foveated-nh3ld", {}),
                             ("NH3LD + temporal, levels from variance", "foveated-nh3ld-temporal",
                              {"nh_denoise.levels_from": "variance"})]:
    r = tandem.Renderer(scene, pipeline=pipeline, width=args.width, height=args.height,
                        stereo=True, sets=sets)
    out = r.render(frames=args.frames)
    m = tandem.compare(truth, out["output"])
    print(f"| {name} | {r.timings()['frame']:.1f} | {m['ssim']:.4f} | {m['psnr']:.1f} |")
