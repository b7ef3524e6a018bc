#!/usr/bin/env python3
"""Writes scenes/foveated_pink_room.json and scenes/foveated_forest.json, the interior and the
outdoor scene of Peres 2022's Table 3 kind, from built-in shapes only (the statue is the
procedural trefoil knot, so the scene needs no file outside the repository).
Deterministic: re-running gives the same files."""
import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "..", "scenes")

def obj(name, shape, material, position, scale=(1, 1, 1), rotation=(0, 0, 0), **extra):
    o = {"name": name, "material": material, "position": list(position), "scale": list(scale),
         "rotation": list(rotation)}
    if shape.endswith(".obj"):
        o["file"] = shape
    else:
        o["shape"] = shape
    o.update(extra)
    return o


def pink_room():
    """An 8 x 3 x 6 m room with pink walls, a window the sun shines through and two ceiling
    lamps: 1 directional + 2 point lights, as the thesis' Pink Room."""
    mats = {
        "pink": {"diffuse": [0.86, 0.52, 0.58]},
        "ceiling": {"diffuse": [0.92, 0.85, 0.86]},
        "floor": {"diffuse": [0.55, 0.38, 0.27]},
        "fabric": {"diffuse": [0.75, 0.25, 0.38]},
        "wood": {"diffuse": [0.45, 0.3, 0.2]},
        "porcelain": {"diffuse": [0.9, 0.88, 0.85]},
        "teal": {"diffuse": [0.2, 0.55, 0.55]},
        "cream": {"diffuse": [0.95, 0.9, 0.75]},
    }
    o = [
        obj("floor", "plane", "floor", (0, 0, 0), (4, 1, 3), subdivisions=8),
        obj("ceiling", "plane", "ceiling", (0, 3, 0), (4, 1, 3), (180, 0, 0)),
        obj("back_wall", "plane", "pink", (0, 1.5, -3), (4, 1, 1.5), (90, 0, 0)),
        obj("front_wall", "plane", "pink", (0, 1.5, 3), (4, 1, 1.5), (-90, 0, 0)),
        obj("left_wall", "plane", "pink", (-4, 1.5, 0), (1.5, 1, 3), (0, 0, -90)),
        # The right wall is four boxes around a window (z -1 ... 0.6, y 1 ... 2.4).
        obj("right_wall_low", "cube", "pink", (4.05, 0.5, 0), (0.05, 0.5, 3)),
        obj("right_wall_high", "cube", "pink", (4.05, 2.7, 0), (0.05, 0.3, 3)),
        obj("right_wall_back", "cube", "pink", (4.05, 1.7, -2), (0.05, 0.7, 1)),
        obj("right_wall_front", "cube", "pink", (4.05, 1.7, 1.8), (0.05, 0.7, 1.2)),
        obj("sofa_seat", "cube", "fabric", (-1.5, 0.25, -2.35), (1.2, 0.25, 0.45)),
        obj("sofa_back", "cube", "fabric", (-1.5, 0.75, -2.8), (1.2, 0.5, 0.15)),
        obj("sofa_arm_l", "cube", "fabric", (-2.75, 0.45, -2.4), (0.12, 0.45, 0.5)),
        obj("sofa_arm_r", "cube", "fabric", (-0.25, 0.45, -2.4), (0.12, 0.45, 0.5)),
        obj("table_top", "cube", "wood", (0.6, 0.72, -0.6), (0.7, 0.03, 0.45)),
        obj("rug", "cube", "teal", (0.2, 0.005, -0.9), (1.8, 0.005, 1.2)),
        obj("statue", "knot", "porcelain", (0.5, 0.99, -0.6), (0.24, 0.24, 0.24), (0, 30, 0)),
        obj("ball", "sphere", "teal", (2.6, 0.45, -1.9), (0.45, 0.45, 0.45), slices=64, stacks=32),
        obj("ball_small", "sphere", "cream", (1.9, 0.2, -2.3), (0.2, 0.2, 0.2), slices=48, stacks=24),
        obj("shelf", "cube", "wood", (-3.75, 1.6, 0.5), (0.22, 0.03, 1.0)),
        obj("cabinet", "cube", "cream", (-3.5, 0.5, 1.8), (0.45, 0.5, 0.6)),
    ]
    for i, (x, z) in enumerate([(0.05, -0.9), (1.15, -0.9), (0.05, -0.3), (1.15, -0.3)]):
        o.append(obj("table_leg%d" % i, "cube", "wood", (x, 0.35, z), (0.03, 0.35, 0.03)))
    for i in range(5):
        o.append(obj("vase%d" % i, "sphere", "porcelain", (-3.75, 1.75, 0.0 + 0.25 * i),
                     (0.08, 0.12, 0.08), slices=32, stacks=16))
    lights = [
        {"type": "directional", "name": "sun", "direction": [-1.0, -0.55, 0.15],
         "intensity": 4.0, "color": [1.0, 0.92, 0.8]},
        {"type": "point", "name": "lamp_left", "position": [-2.0, 2.3, -1.0], "intensity": 4.0,
         "color": [1.0, 0.8, 0.6]},
        {"type": "point", "name": "lamp_right", "position": [1.5, 2.3, 1.0], "intensity": 4.0,
         "color": [1.0, 0.8, 0.6]},
    ]
    return {
        "materials": mats, "objects": o, "lights": lights,
        "ambient": [0, 0, 0],
        "skybox": {"color": [0.55, 0.7, 0.95]},
        "camera": {"position": [3.2, 1.65, 2.6], "lookAt": [-1.0, 1.0, -1.6], "vfov": 75},
        "cameraPath": [
            {"time": 0, "position": [3.2, 1.65, 2.6], "lookAt": [-1.0, 1.0, -1.6]},
            {"time": 5, "position": [2.0, 1.65, 2.7], "lookAt": [-1.2, 0.9, -2.0]},
            {"time": 10, "position": [0.5, 1.65, 2.6], "lookAt": [0.3, 0.9, -2.5]},
        ],
        "stereo": {"enabled": True},
    }


def forest():
    """A night clearing: ~200 trees (about 200k triangles) along a path lit by 80 lanterns
    (point lights), as the thesis' Forest (198,541 triangles, 80 point lights)."""
    rnd = random.Random(4)
    mats = {
        "ground": {"diffuse": [0.25, 0.3, 0.15]},
        "path": {"diffuse": [0.5, 0.45, 0.38]},
        "bark": {"diffuse": [0.3, 0.2, 0.12]},
        "leaves": {"diffuse": [0.18, 0.42, 0.16]},
        "leaves_dark": {"diffuse": [0.12, 0.3, 0.12]},
        "stone": {"diffuse": [0.55, 0.55, 0.52]},
    }
    o = [
        obj("ground", "plane", "ground", (0, 0, 0), (60, 1, 60), subdivisions=16),
        obj("path", "cube", "path", (0, 0.005, 0), (1.6, 0.005, 45)),
    ]
    trees = 0
    for gx in range(-7, 8):
        for gz in range(-7, 8):
            x = gx * 5.5 + rnd.uniform(-2, 2)
            z = gz * 5.5 + rnd.uniform(-2, 2)
            if abs(x) < 3.5 or trees >= 190:
                continue
            h = rnd.uniform(2.5, 4.5)
            r = rnd.uniform(1.0, 1.8)
            o.append(obj("trunk%d" % trees, "cube", "bark", (x, h / 2, z), (0.15, h / 2, 0.15)))
            o.append(obj("crown%d" % trees, "sphere", "leaves" if trees % 3 else "leaves_dark",
                         (x, h + r * 0.9, z), (r, r * 1.5, r), slices=32, stacks=16))
            trees += 1
    for i in range(12):
        o.append(obj("rock%d" % i, "sphere", "stone",
                     (rnd.choice([-1, 1]) * rnd.uniform(2.2, 3.2), 0.1, rnd.uniform(-40, 40)),
                     (rnd.uniform(0.3, 0.6), 0.3, rnd.uniform(0.3, 0.6)), slices=24, stacks=12))
    lights = []
    for i in range(80):
        if i < 40:  # lanterns along both edges of the path
            x, z = (-2.0 if i % 2 else 2.0), -39 + 2 * i
        else:
            x, z = rnd.uniform(-38, 38), rnd.uniform(-38, 38)
        lights.append({"type": "point", "name": "lantern%d" % i, "position": [x, 1.3, z],
                       "intensity": 2.5, "color": [1.0, 0.75, 0.45], "range": 25})
    return {
        "materials": mats, "objects": o, "lights": lights,
        "ambient": [0, 0, 0],
        "skybox": {"color": [0.03, 0.04, 0.08]},
        "camera": {"position": [0.3, 1.7, 30], "lookAt": [0, 1.6, 0], "vfov": 75},
        "cameraPath": [
            {"time": 0, "position": [0.3, 1.7, 30], "lookAt": [0, 1.6, 0]},
            {"time": 5, "position": [-0.3, 1.7, 15], "lookAt": [0.5, 1.6, -10]},
            {"time": 10, "position": [0.3, 1.7, 0], "lookAt": [-0.5, 1.6, -25]},
        ],
        "stereo": {"enabled": True},
    }


def write(name, scene):
    with open(os.path.join(SCENES, name), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    write("foveated_pink_room.json", pink_room())
    write("foveated_forest.json", forest())
