"""Walewski et al. 2019's time-quality trade: hybrid-heuristic at several budgets T against rt-only (the same
shading, every ray traced), plotted as ms per frame against SSIM. The README's Python example."""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import tandem

scene, w, h = "scenes/atrium_spheres.json", 320, 180
rt = tandem.Renderer(scene, pipeline="rt-only", width=w, height=h)
rt.render()  # the first frame builds the BVH
truth = rt.render()["output"]
points = []
for budget in [0, 3e4, 1e5, 3e5, 1e6]:
    r = tandem.Renderer(scene, pipeline="hybrid-heuristic", width=w, height=h)
    r.set("heuristic.budget", budget)
    r.render()  # the first frame builds the BVH and the probes
    out = r.render()
    points.append((r.timings()["frame"], tandem.compare(truth, out["output"])["ssim"], budget))
    print(f"T = {budget:9.0f}: {points[-1][0]:6.1f} ms, SSIM {points[-1][1]:.4f}")
plt.plot([p[0] for p in points], [p[1] for p in points], "o-", label="hybrid-heuristic")
plt.axvline(rt.timings()["frame"], color="gray", linestyle="--", label="rt-only")
for ms, ssim, budget in points:
    plt.annotate(f"T={budget:g}", (ms, ssim))
plt.xlabel("ms per frame")
plt.ylabel("SSIM against rt-only")
plt.legend()
plt.savefig("budget_sweep.png", dpi=120)
