"""Tan et al. 2022, Table 2 from Python: the three shots of the DoF courtyard (background-dominant BG,
mixed M, foreground close-up FG) through post-process DoF, hybrid DoF and lens rays everywhere,
each timed and compared with distributed ray tracing of the same shading (the Whitted thin-lens
reference). `tandem experiment hybrid-dof` is the full version."""
import argparse
import tandem

ap = argparse.ArgumentParser()
ap.add_argument("--width", type=int, default=960)
ap.add_argument("--height", type=int, default=540)
ap.add_argument("--frames", type=int, default=8, help="frames rendered (temporal passes converge)")
ap.add_argument("--spp", type=int, default=256, help="reference samples per pixel")
args = ap.parse_args()

print("| shot | pipeline | ms / frame | SSIM | PSNR dB |")
print("| --- | --- | ---: | ---: | ---: |")
for shot in ["BG", "M", "FG"]:
    scene = {"BG": "scenes/dof_bg.json", "M": "scenes/dof_mixed.json", "FG": "scenes/dof_fg.json"}[shot]
    truth = tandem.reference(scene, integrator="whitted", spp=args.spp, width=args.width,
                             height=args.height)["output"]
    for pipeline in ["postfx-dof", "hybrid-dof", "rt-dof"]:
        r = tandem.Renderer(scene, pipeline=pipeline, width=args.width, height=args.height)
        out = r.render(frames=args.frames)
        m = tandem.compare(truth, out["output"])
        print(f"| {shot} | {pipeline} | {r.timings()['frame']:.1f} | {m['ssim']:.4f} | {m['psnr']:.1f} |")
