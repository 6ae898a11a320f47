#!/usr/bin/env python3
"""Writes the scenes of scenes/stress/, made to scatter rays (issue "Incoherent
rays at full speed"): sticks.json, thousands of thin cylinders in every
direction; mirror-room.json, a closed room of mirrors with glass and matte
balls; glass-in-glass.json, rows of glass spheres nested three deep, each
absorbing its own colour; glass-rods.json, long rods of glass and metal
crossing in every direction over a floor, shadows passing through glass.
Deterministic: run it again and the files are the
same. Usage: tools/stress_scenes.py [FOLDER] (default scenes/stress)."""
import json
import math
import os
import random
import sys


def num(x):
    return round(x, 5)


def vec(v):
    return [num(c) for c in v]


def write(folder, name, scene):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write("{\n")
        keys = list(scene)
        for i, k in enumerate(keys):
            end = ",\n" if i + 1 < len(keys) else "\n"
            if k == "objects":
                f.write('  "objects": [\n')
                objs = scene[k]
                for j, o in enumerate(objs):
                    f.write("    " + json.dumps(o, separators=(", ", ": ")))
                    f.write(",\n" if j + 1 < len(objs) else "\n")
                f.write("  ]" + end)
            else:
                f.write("  " + json.dumps(k) + ": " +
                        json.dumps(scene[k], separators=(", ", ": ")) + end)
        f.write("}\n")


def unit(rng):
    z = rng.uniform(-1, 1)
    a = rng.uniform(0, 2 * math.pi)
    r = math.sqrt(1 - z * z)
    return (r * math.cos(a), r * math.sin(a), z)


def rod(material, c, d, half, base_radius, apex_radius):
    """A cone centred at c along unit direction d, 2 half long."""
    return {"type": "cone", "material": material,
            "base": vec([c[k] - half * d[k] for k in range(3)]), "base_radius": num(base_radius),
            "apex": vec([c[k] + half * d[k] for k in range(3)]), "apex_radius": num(apex_radius)}


def sticks(rng):
    objs = []
    for i in range(3000):
        c = [rng.uniform(-5, 5) for _ in range(3)]
        d = unit(rng)
        half = rng.uniform(0.5, 1.5)
        r = rng.uniform(0.01, 0.03)
        objs.append(rod(["steel", "copper", "chalk"][i % 3], c, d, half, r, r))
    return {
        "camera": {"from": [9, 7, 13], "at": [0, 0, 0], "up": [0, 1, 0], "fov": 50},
        "image": {"width": 512, "height": 512},
        "background": [0.05, 0.05, 0.08],
        "ambient": [0.2, 0.2, 0.2],
        "lights": [{"position": [10, 12, 8], "color": [0.7, 0.7, 0.7]},
                   {"position": [-9, 6, -4], "color": [0.4, 0.4, 0.5]},
                   {"position": [2, -10, 9], "color": [0.3, 0.3, 0.3]}],
        "materials": {
            "steel": {"color": [0.7, 0.72, 0.75], "kd": 0.3, "ks": 0.6, "h": 60, "kr": 0.6},
            "copper": {"color": [0.9, 0.5, 0.3], "kd": 0.5, "ks": 0.4, "h": 30, "kr": 0.3},
            "chalk": {"color": [0.9, 0.9, 0.85], "kd": 0.9, "ks": 0.1, "h": 10}},
        "objects": objs}


def quad(material, a, b, c, d):
    return [{"type": "triangle", "material": material, "vertices": [a, b, c]},
            {"type": "triangle", "material": material, "vertices": [a, c, d]}]


def mirror_room(rng):
    s = 4
    p = [[x, y, z] for x in (-s, s) for y in (0, 2 * s) for z in (-s, s)]
    # corners: index = 4 x + 2 y + z over the two values of each
    def P(x, y, z):
        return p[4 * x + 2 * y + z]
    objs = []
    objs += quad("floor", P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1))
    objs += quad("mirror", P(0, 1, 0), P(0, 1, 1), P(1, 1, 1), P(1, 1, 0))
    objs += quad("mirror", P(0, 0, 0), P(0, 0, 1), P(0, 1, 1), P(0, 1, 0))
    objs += quad("mirror", P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1))
    objs += quad("mirror", P(0, 0, 0), P(0, 1, 0), P(1, 1, 0), P(1, 0, 0))
    objs += quad("mirror", P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1))
    for i in range(40):
        r = rng.uniform(0.2, 0.6)
        c = [rng.uniform(-s + r, s - r), rng.uniform(r, 2 * s - r), rng.uniform(-s + r, s - r)]
        if abs(c[0] - 1.5) < 1 and abs(c[1] - 2) < 1 and abs(c[2] - 3) < 1:
            continue  # keep the camera clear
        objs.append({"type": "sphere", "material": ["glass", "red", "gold"][i % 3],
                     "center": vec(c), "radius": num(r)})
    return {
        "camera": {"from": [1.5, 2, 3], "at": [-1, 3.5, -4], "up": [0, 1, 0], "fov": 70},
        "image": {"width": 512, "height": 512},
        "background": [0, 0, 0],
        "ambient": [0.3, 0.3, 0.3],
        "lights": [{"position": [0, 7, 0], "color": [0.8, 0.8, 0.8]},
                   {"position": [2.5, 1, -2.5], "color": [0.4, 0.35, 0.3]}],
        "materials": {
            "floor": {"color": [0.6, 0.6, 0.6], "kd": 0.8,
                      "texture": {"type": "checker-planar", "odd": [0.8, 0.8, 0.8],
                                  "even": [0.2, 0.2, 0.3], "size": 1}},
            "mirror": {"color": [0.9, 0.9, 0.9], "kd": 0.1, "ks": 0.8, "h": 200, "kr": 0.85},
            "glass": {"color": [1, 1, 1], "ka": 0.01, "kd": 0.01, "ks": 0.9, "h": 80,
                      "kr": 0.1, "kt": 0.9, "ior": 1.5},
            "red": {"color": [0.8, 0.1, 0.1], "kd": 0.8, "ks": 0.3, "h": 20},
            "gold": {"color": [0.9, 0.7, 0.2], "kd": 0.4, "ks": 0.6, "h": 60, "kr": 0.5}},
        "objects": objs}


def glass_in_glass(rng):
    objs = [{"type": "plane", "material": "floor", "normal": [0, 1, 0], "point": [0, 0, 0]}]
    shells = [("outer", 1.0), ("middle", 0.7), ("inner", 0.4)]
    for i in range(6):
        for j in range(6):
            c = [2.4 * (i - 2.5) + rng.uniform(-0.2, 0.2), 1.0,
                 2.4 * (j - 2.5) + rng.uniform(-0.2, 0.2)]
            for name, r in shells:
                objs.append({"type": "sphere", "material": name, "center": vec(c),
                             "radius": r})
    return {
        "camera": {"from": [0, 9, 12], "at": [0, 0.5, 0], "up": [0, 1, 0], "fov": 55},
        "image": {"width": 512, "height": 512},
        "background": [0.3, 0.4, 0.6],
        "ambient": [0.5, 0.5, 0.5],
        "lights": [{"position": [-6, 12, 8], "color": [1, 1, 1]}],
        "materials": {
            "floor": {"color": [1, 1, 1], "ka": 0.1, "kd": 0.9,
                      "texture": {"type": "checker-planar", "odd": [0.9, 0.9, 0.9],
                                  "even": [0.1, 0.1, 0.1], "size": 1}},
            "outer": {"color": [1, 1, 1], "ka": 0.01, "kd": 0.01, "ks": 0.9, "h": 80,
                      "kr": 0.1, "kt": 0.9, "ior": 1.5, "absorb": [0.05, 0.2, 0.3]},
            "middle": {"color": [1, 1, 1], "ka": 0.01, "kd": 0.01, "ks": 0.9, "h": 80,
                       "kr": 0.1, "kt": 0.9, "ior": 1.33, "absorb": [0.3, 0.05, 0.2]},
            "inner": {"color": [1, 1, 1], "ka": 0.01, "kd": 0.01, "ks": 0.9, "h": 80,
                      "kr": 0.1, "kt": 0.9, "ior": 2.4, "absorb": [0.2, 0.3, 0.05]}},
        "objects": objs}


def glass_rods(rng):
    objs = [{"type": "plane", "material": "floor", "normal": [0, 1, 0], "point": [0, -3, 0]}]
    for i in range(240):
        c = [rng.uniform(-3, 3), rng.uniform(-2, 3), rng.uniform(-3, 3)]
        d = unit(rng)
        half = rng.uniform(0.8, 2.5)
        r = rng.uniform(0.04, 0.12)
        objs.append(rod(["glass", "steel", "tinted"][i % 3], c, d, half, r,
                        r * rng.uniform(0.5, 1)))
    return {
        "camera": {"from": [7, 5, 10], "at": [0, 0, 0], "up": [0, 1, 0], "fov": 50},
        "image": {"width": 512, "height": 512},
        "background": [0.2, 0.25, 0.35],
        "ambient": [0.3, 0.3, 0.3],
        "lights": [{"position": [8, 12, 6], "color": [0.8, 0.8, 0.8]},
                   {"position": [-8, 6, -3], "color": [0.4, 0.4, 0.5]}],
        "materials": {
            "floor": {"color": [1, 1, 1], "ka": 0.1, "kd": 0.9,
                      "texture": {"type": "checker-planar", "odd": [0.9, 0.9, 0.9],
                                  "even": [0.2, 0.2, 0.2], "size": 1}},
            "glass": {"color": [1, 1, 1], "ka": 0.01, "kd": 0.01, "ks": 0.9, "h": 80,
                      "kr": 0.1, "kt": 0.9, "ior": 1.5},
            "tinted": {"color": [1, 1, 1], "ka": 0.01, "kd": 0.01, "ks": 0.9, "h": 80,
                       "kr": 0.1, "kt": 0.85, "ior": 1.4, "absorb": [0.6, 0.2, 0.05]},
            "steel": {"color": [0.7, 0.72, 0.75], "kd": 0.3, "ks": 0.6, "h": 60, "kr": 0.6}},
        "objects": objs}


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "stress")
    os.makedirs(folder, exist_ok=True)
    write(folder, "sticks.json", sticks(random.Random(1)))
    write(folder, "mirror-room.json", mirror_room(random.Random(2)))
    write(folder, "glass-in-glass.json", glass_in_glass(random.Random(3)))
    write(folder, "glass-rods.json", glass_rods(random.Random(4)))


if __name__ == "__main__":
    main()
