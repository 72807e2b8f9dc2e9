#!/usr/bin/env python3
"""The hand count of the TORCS track street-1 (docs/test-scenes.md), made reproducible: reads
the converted model (data/cache/torcs-data/street-1/street-1.ac, from scripts/fetch-test-data)
and sorts its objects by what they show, judged by their base texture (and, for two cases, by
their name), as a person looking at the textures and the rendered track sorted them.

Usage: torcs-street-1-census.py [street-1.ac] [--list]

One AC3D object with surfaces becomes one osg::Geode holding one osg::Geometry when OSG's ac
plugin loads this model (1436 of each), so "geometries" below are also the loaded drawables.
Buildings are counted as objects: the building-textured geometries whose footprints (x/z
boxes) overlap or touch within 0.5 m are one building, if they use the same texture (walls2.rgb, roof1.rgb and the untextured roof edge
count as one texture: the houses made of them mix the three). Trees: every TREEP* object is one tree (two or three crossed cards).
"""
import collections
import os
import re
import sys

# texture (or object name) -> category; first match wins
RULES = [
    ("name", r"^SPHERE", "street-lamp"),          # lamp posts textured with tr-road1-pit.rgb
    ("name", r"^REBTOITF$", "building"),          # an untextured roof edge of building MURF/TOITF
    ("tex", r"^(house|walls|walls2|roof1)\.rgb$|^tr-building\d|^tr-house-arbor", "building"),
    ("tex", r"^(tr-road1_n|tr-asphalt-aa-bw1_n|tr-road1-pit|tr-road1-pit_n)\.rgb$|^tr-asphalt-2-aa-r_n\.png$",
     "street"),
    ("tex", r"^tr-curb", "street-curb"),
    ("tex", r"^(treeg10_n|tree-new_n|tree-poplar_n)\.rgb$", "tree"),
    ("tex", r"^tree-border_n", "tree-line-backdrop"),
    ("tex", r"^grass-aa", "terrain-grass"),
    ("tex", r"^tr-sand", "terrain-sand"),
    ("tex", r"^town-border-arbor", "skyline-backdrop"),
    ("tex", r"^(tr-barrier|tr-tirewall|barr1)\.rgb$", "barrier"),
    ("tex", r"^(truck0|truck_arbor_ctd_n)\.rgb$", "truck"),
    ("tex", r"^(std|concdal|poutre3_arbor_n|torcs1)\.rgb$|^tr-spec\.png$", "grandstand"),
    ("tex", r"^(pylon\d|concrete|concrete2)\.rgb$|^texte1\.png$", "pylon-post-sign"),
]


def read_objects(path):
    lines = open(path, encoding="latin-1").read().split("\n")
    objs, stack = [], []
    cur = None
    i = 0
    while i < len(lines):
        t = lines[i].split()
        if not t:
            i += 1
            continue
        k = t[0]
        if k == "OBJECT":
            while stack and stack[-1][0] == 0:
                stack.pop()
            parent = stack[-1][1] if stack else None
            if stack:
                stack[-1][0] -= 1
            cur = {"name": "", "tex": parent["tex"] if parent else None, "loc": [0.0] * 3,
                   "ploc": [a + b for a, b in zip(parent["ploc"], parent["loc"])] if parent else [0.0] * 3,
                   "tris": 0, "mn": [1e30] * 3, "mx": [-1e30] * 3}
            objs.append(cur)
        elif k == "name":
            cur["name"] = lines[i][5:].strip().strip('"')
        elif k == "texture":
            cur["tex"] = lines[i].split('"')[1]
        elif k == "loc":
            cur["loc"] = [float(x) for x in t[1:4]]
        elif k == "numvert":
            n = int(t[1])
            off = [a + b for a, b in zip(cur["ploc"], cur["loc"])]
            for j in range(n):
                v = [float(x) for x in lines[i + 1 + j].split()[:3]]
                for c in range(3):
                    cur["mn"][c] = min(cur["mn"][c], v[c] + off[c])
                    cur["mx"][c] = max(cur["mx"][c], v[c] + off[c])
            i += n
        elif k == "refs":
            cur["tris"] += max(int(t[1]) - 2, 0)
        elif k == "kids":
            stack.append([int(t[1]), cur])
        i += 1
    return [o for o in objs if o["tris"] > 0]


def category(o):
    for field, pattern, cat in RULES:
        value = o["name"] if field == "name" else (o["tex"] or "")
        if re.search(pattern, value):
            return cat
    return "other"


def kit(o):
    """Objects of one building share a texture, or are walls2 + roof1 + the untextured edge."""
    tex = o["tex"] or ""
    return "walls2+roof1" if tex in ("walls2.rgb", "roof1.rgb", "") else tex


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    here = os.path.dirname(os.path.abspath(__file__))
    path = args[0] if args else os.path.join(here, "../cache/torcs-data/street-1/street-1.ac")
    objs = read_objects(path)
    agg = collections.defaultdict(lambda: [0, 0])
    for o in objs:
        o["cat"] = category(o)
        agg[o["cat"]][0] += 1
        agg[o["cat"]][1] += o["tris"]
    print("%-20s %10s %9s" % ("category", "geometries", "triangles"))
    for cat, (n, tris) in sorted(agg.items()):
        print("%-20s %10d %9d" % (cat, n, tris))
    print("%-20s %10d %9d" % ("total", len(objs), sum(o["tris"] for o in objs)))

    b = [o for o in objs if o["cat"] == "building"]
    parent = list(range(len(b)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    for i in range(len(b)):
        for j in range(i + 1, len(b)):
            if kit(b[i]) == kit(b[j]) and all(
                    b[i]["mn"][k] <= b[j]["mx"][k] + 0.5 and b[j]["mn"][k] <= b[i]["mx"][k] + 0.5 for k in (0, 2)):
                parent[find(i)] = find(j)
    clusters = collections.defaultdict(list)
    for i, o in enumerate(b):
        clusters[find(i)].append(o)
    tall = [c for c in clusters.values() if max(o["mx"][1] for o in c) - min(o["mn"][1] for o in c) > 30]
    print("buildings: %d (%d high-rises over 30 m, %d houses)" % (len(clusters), len(tall), len(clusters) - len(tall)))
    trees = [o for o in objs if o["cat"] == "tree"]
    print("trees: %d (%s)" % (len(trees), ", ".join("%s %d" % kv for kv in
                                                   sorted(collections.Counter(o["tex"] for o in trees).items()))))
    lamps = sum(o["tris"] for o in objs if o["cat"] == "street-lamp") // 90
    print("street lamps: %d (90 triangles each)" % lamps)
    if "--list" in sys.argv:
        for c in sorted(clusters.values(), key=lambda c: min(o["mn"][0] for o in c)):
            mn = [min(o["mn"][k] for o in c) for k in range(3)]
            mx = [max(o["mx"][k] for o in c) for k in range(3)]
            print("  building: %2d geometries %4d tris, x %.0f..%.0f, height %.0f m, AC z %.0f..%.0f, %s" % (
                len(c), sum(o["tris"] for o in c), mn[0], mx[0], mx[1] - mn[1], mn[2], mx[2],
                ",".join(sorted(set(o["tex"] or "-" for o in c)))))


if __name__ == "__main__":
    main()
