#!/usr/bin/env python3
"""Writes a scene file: a Cornell box (cornell_spheres.json) lit by N small coloured point lights
in a grid through the room, each with the given range (0: none, physical inverse square).
The scene of docs/benchmarks.md's lights-at-scale figures.

  python3 scripts/many_lights.py 1000 0.35 > /tmp/lights_1000.json
  tandem bench /tmp/lights_1000.json --pipeline rt-only --width 1280 --height 720
"""
import json
import os
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: many_lights.py COUNT RANGE")
    try:
        count, reach = int(sys.argv[1]), float(sys.argv[2])
    except ValueError:
        sys.exit("many_lights.py: COUNT must be an integer and RANGE a number")
    if not 1 <= count <= 100000 or not 0 <= reach <= 100:
        sys.exit("many_lights.py: COUNT must be in [1, 100000] and RANGE in [0, 100]")
    side = max(1, round(count ** (1 / 3)))
    lights = []
    for i in range(count):
        x, y, z = i % side, (i // side) % side, i // (side * side)
        light = {
            "type": "point",
            "position": [-0.9 + 1.8 * (x + 0.5) / side, 0.05 + 1.8 * (y + 0.5) / side,
                         -0.9 + 1.8 * ((z % side) + 0.5) / side],
            # The same total power whatever the count.
            "intensity": (20.0 if reach > 0 else 4.0) / count,
            "color": [0.5 + 0.5 * ((i * 37) % 11) / 10, 0.5 + 0.5 * ((i * 17) % 13) / 12,
                      0.5 + 0.5 * ((i * 7) % 5) / 4],
        }
        if reach > 0:
            light["range"] = reach
        lights.append(light)
    scenes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
    base = os.path.normpath(os.path.join(scenes, "cornell_spheres.json"))
    json.dump({"base": base, "lights": lights}, sys.stdout)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
