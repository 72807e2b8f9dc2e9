#!/usr/bin/env python3
"""Counts what a scene holds, with the stock OpenSceneGraph tools only (no project build):
the scene is read by `osgconv` (optimizer off, so the graph is as osgDB loads it) into .osgt
text, which this script walks. ProxyNode files are read the same way (relative to the scene's
folder) and placed under their parents' transforms.

Usage: scene-stats.py SCENE [--names] [--json]

Prints: nodes per class, Geodes, Geometries, triangles (TRIANGLES, QUADS as 2, POLYGON,
TRIANGLE_STRIP and TRIANGLE_FAN as n-2), vertices, the world-space bounding box (all
transforms applied), and every texture image: file, size, pixel format as osgDB loaded it
(GL_RGB, GL_RGBA, GL_LUMINANCE, GL_LUMINANCE_ALPHA), and for images with alpha the share of
texels that are fully transparent (alpha 0) and partly transparent (0 < alpha < 255).
--names also lists every named node with the path of names above it.
"""
import base64
import json
import os
import subprocess
import sys
import tempfile

PIXEL_FORMATS = {0x1907: "GL_RGB", 0x1908: "GL_RGBA", 0x1909: "GL_LUMINANCE",
                 0x190A: "GL_LUMINANCE_ALPHA", 0x1906: "GL_ALPHA", 0x80E0: "GL_BGR",
                 0x80E1: "GL_BGRA", 0x1903: "GL_RED", 0x8227: "GL_RG"}
CHANNELS = {"GL_RGB": 3, "GL_RGBA": 4, "GL_LUMINANCE": 1, "GL_LUMINANCE_ALPHA": 2,
            "GL_ALPHA": 1, "GL_BGR": 3, "GL_BGRA": 4, "GL_RED": 1, "GL_RG": 2}


class Block:
    __slots__ = ("head", "items")

    def __init__(self, head):
        self.head = head
        self.items = []   # str lines or Block

    def prop(self, key):
        for it in self.items:
            if isinstance(it, str) and (it == key or it.startswith(key + " ")):
                return it[len(key):].strip()
        return None

    def block(self, key):
        for it in self.items:
            if isinstance(it, Block) and it.head.split()[0] == key:
                return it
        return None

    def blocks(self):
        return [it for it in self.items if isinstance(it, Block)]


def parse_osgt(text):
    root = Block("ROOT")
    stack = [root]
    for raw in text.split("\n"):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if line == "}":
            stack.pop()
        elif line.endswith(" }") and line.startswith('"'):   # the last line of image data
            stack[-1].items.append(line[:-1].strip())
            stack.pop()
        elif line.endswith("{"):
            b = Block(line[:-1].strip())
            stack[-1].items.append(b)
            stack.append(b)
        else:
            stack[-1].items.append(line)
    return root


def unquote(s):
    return s[1:-1] if s and len(s) >= 2 and s[0] == '"' and s[-1] == '"' else s


def numbers(block):
    out = []
    for it in block.items:
        if isinstance(it, str):
            out.extend(float(x) for x in it.split())
    return out


def mat_mul(a, b):   # row-vector convention (OSG): p' = p * M
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


IDENTITY = [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


class Stats:
    def __init__(self):
        self.classes = {}
        self.geodes = 0
        self.geometries = 0
        self.triangles = 0
        self.vertices = 0
        self.bbmin = [float("inf")] * 3
        self.bbmax = [float("-inf")] * 3
        self.images = {}   # file -> info
        self.named = []    # (path, class, name, triangles below)
        self.by_id = {}
        self.warnings = []


def triangles_of(prim):
    cls = prim.head.split()[0]
    mode = (prim.prop("Mode") or "").split()[0] if prim.prop("Mode") else ""
    def tris(n):
        if mode == "TRIANGLES":
            return n // 3
        if mode == "QUADS":
            return n // 4 * 2
        if mode in ("POLYGON", "TRIANGLE_STRIP", "TRIANGLE_FAN", "QUAD_STRIP"):
            return max(n - 2, 0)
        return 0
    if cls == "osg::DrawArrays":
        return tris(int(prim.prop("Count") or 0))
    vec = prim.block("vector")
    vals = [int(v) for v in numbers(vec)] if vec else []
    if cls == "osg::DrawArrayLengths":
        return sum(tris(n) for n in vals)
    if cls.startswith("osg::DrawElements"):
        return tris(len(vals))
    return 0


def image_info(img, folder):
    info = {}
    fn = unquote(img.prop("FileName") or "")
    info["path"] = fn
    info["file"] = os.path.join(os.path.basename(os.path.dirname(fn)), os.path.basename(fn)) \
        if os.path.basename(fn) in ("tex.png", "texture.png") else os.path.basename(fn)
    size = (img.prop("Size") or "0 0 0").split()
    info["size"] = "%sx%s" % (size[0], size[1])
    pf = int((img.prop("PixelFormat") or "0").split()[0])
    info["format"] = PIXEL_FORMATS.get(pf, hex(pf))
    data = img.block("Data")
    ch = CHANNELS.get(info["format"], 0)
    if data is not None and info["format"] in ("GL_RGBA", "GL_LUMINANCE_ALPHA", "GL_BGRA"):
        raw = base64.b64decode("".join(unquote(s) if isinstance(s, str) else "" for s in data.items)
                               .replace('"', ""))
        alpha = raw[ch - 1::ch]
        n = len(alpha) or 1
        zero = alpha.count(0)
        full = alpha.count(255)
        info["alpha0"] = round(zero / n, 3)
        info["alphaPartial"] = round((n - zero - full) / n, 3)
    return info


def load(path, folder_for_proxies):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "scene.osgt")
        env = dict(os.environ, OSG_OPTIMIZER="OFF")
        r = subprocess.run(["osgconv", path, out], cwd=folder_for_proxies, env=env,
                           capture_output=True, text=True)
        if not os.path.exists(out):
            sys.exit("scene-stats: osgconv failed on %s:\n%s%s" % (path, r.stdout, r.stderr))
        warn = [l for l in (r.stdout + r.stderr).splitlines() if "Data written" not in l and l.strip()]
        with open(out, encoding="latin-1") as f:
            return parse_osgt(f.read()), warn


def walk(b, st, matrix, path, folder, depth=0):
    cls = b.head.split()[0]
    uid = b.prop("UniqueID")
    if uid is not None and len(b.items) <= 1:    # a reference to an object written before
        b = st.by_id.get((id(st.current), uid), b)
    elif uid is not None:
        st.by_id[(id(st.current), uid)] = b
    st.classes[cls] = st.classes.get(cls, 0) + 1
    name = unquote(b.prop("Name") or "")
    tri_before = st.triangles
    if cls == "osg::MatrixTransform":
        m = b.block("Matrix")
        if m is not None:
            v = numbers(m)
            matrix = mat_mul([v[0:4], v[4:8], v[8:12], v[12:16]], matrix)
    ss = b.block("StateSet")
    if ss is not None:
        for img in find_images(ss):
            info = image_info(img, folder)
            st.images.setdefault(os.path.normpath(os.path.join(folder, info["path"])), info)
    if cls == "osg::Geode":
        st.geodes += 1
    if cls == "osg::Geometry":
        st.geometries += 1
        pl = b.block("PrimitiveSetList")
        if pl is not None:
            for p in pl.blocks():
                st.triangles += triangles_of(p)
        va = b.block("VertexArray")
        if va is not None:
            arr = va.blocks()[0]
            vec = arr.block("vector")
            vals = numbers(vec) if vec else []
            st.vertices += len(vals) // 3
            for i in range(0, len(vals) - 2, 3):
                x, y, z = vals[i:i + 3]
                p = [x * matrix[0][j] + y * matrix[1][j] + z * matrix[2][j] + matrix[3][j] for j in range(3)]
                for k in range(3):
                    st.bbmin[k] = min(st.bbmin[k], p[k])
                    st.bbmax[k] = max(st.bbmax[k], p[k])
    sub_path = path + [name] if name else path
    children = b.block("Children")
    if children is not None:
        for c in children.blocks():
            walk(c, st, matrix, sub_path, folder, depth + 1)
    drawables = b.block("Drawables")
    if drawables is not None:
        for c in drawables.blocks():
            walk(c, st, matrix, sub_path, folder, depth + 1)
    if cls == "osg::ProxyNode":
        fns = b.block("FileNames")
        for fn in ([unquote(s) for s in fns.items if isinstance(s, str)] if fns else []):
            full = os.path.normpath(os.path.join(folder, fn))
            tree, warn = load(full, os.path.dirname(full))
            st.warnings.extend("%s: %s" % (fn, w) for w in warn)
            saved = st.current
            st.current = tree
            for top in tree.blocks():
                walk(top, st, matrix, sub_path, os.path.dirname(full), depth + 1)
            st.current = saved
    if name:
        st.named.append(("/".join(path), cls, name, st.triangles - tri_before))


def find_images(block):
    out = []
    for it in block.blocks():
        if it.head == "Image TRUE":
            out.append(it)
        else:
            out.extend(find_images(it))
    return out


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        sys.exit(__doc__)
    scene = os.path.abspath(args[0])
    folder = os.path.dirname(scene)
    st = Stats()
    tree, warn = load(scene, folder)
    st.warnings.extend(warn)
    st.current = tree
    for top in tree.blocks():
        walk(top, st, IDENTITY, [], folder)
    size = [st.bbmax[k] - st.bbmin[k] for k in range(3)]
    result = {
        "scene": args[0], "classes": st.classes, "geodes": st.geodes,
        "geometries": st.geometries, "triangles": st.triangles, "vertices": st.vertices,
        "bbox_min": [round(v, 2) for v in st.bbmin], "bbox_max": [round(v, 2) for v in st.bbmax],
        "bbox_size": [round(v, 2) for v in size],
        "textures": sorted(st.images.values(), key=lambda i: i["file"]),
        "warnings": st.warnings,
    }
    if "--json" in sys.argv:
        if "--names" in sys.argv:
            result["named"] = st.named
        print(json.dumps(result, indent=1))
        return
    print("scene: %s" % args[0])
    print("classes: " + ", ".join("%s %d" % kv for kv in sorted(st.classes.items())))
    print("geodes %d, geometries %d, triangles %d, vertices %d" %
          (st.geodes, st.geometries, st.triangles, st.vertices))
    print("bbox min %s max %s size %s" % (result["bbox_min"], result["bbox_max"], result["bbox_size"]))
    formats = {}
    for i in st.images.values():
        formats[i["format"]] = formats.get(i["format"], 0) + 1
    print("textures %d: %s" % (len(st.images), ", ".join("%s %d" % kv for kv in sorted(formats.items()))))
    for i in result["textures"]:
        extra = ""
        if "alpha0" in i:
            extra = "  alpha=0: %.1f%%, 0<alpha<255: %.1f%%" % (100 * i["alpha0"], 100 * i["alphaPartial"])
        print("  %-28s %-9s %-18s%s" % (i["file"], i["size"], i["format"], extra))
    if "--names" in sys.argv:
        for p, cls, name, tris in st.named:
            print("  node %s%s [%s] %d tris" % (p + "/" if p else "", name, cls, tris))
    for w in st.warnings:
        print("warning: " + w)


if __name__ == "__main__":
    main()
