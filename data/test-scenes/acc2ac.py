#!/usr/bin/env python3
"""Converts a TORCS track model (.acc, TORCS's multi-texture AC3D variant) into plain AC3D
(.ac) that OpenSceneGraph's ac plugin (osgdb_ac) reads. Used by scripts/fetch-test-data.

Usage: acc2ac.py IN.acc OUT.ac [TEXTURE_DIR...]

What differs in a .acc and what is done with it:
  - each object has up to four `texture NAME KIND` lines (base, tiled, skids, shad); only the
    `base` texture is kept (osgdb_ac keeps the last texture line it reads, which in a .acc is
    the empty shadow slot);
  - `numvert` lines carry a normal after the position (x y z nx ny nz): the normal is dropped;
  - `refs` lines carry one texture coordinate pair per texture layer: the first is kept;
  - surfaces of type 4 (SURF 0x?4) are triangle strips: they become triangles (type 0, same
    shading/two-sided flags), alternating the winding as a strip does; degenerate triangles
    (a repeated vertex), which TORCS's strips use as joints, are dropped.
Base textures named "(null)" or "empty_texture_no_mapping" are dropped (untextured object).
When TEXTURE_DIRs are given, the script prints, one per line, the base textures the model uses
followed by the folder (first TEXTURE_DIR holding it) or "MISSING".
Geometry, object names, hierarchy, materials, rot/loc/texrep/texoff/crease are kept as they are;
the coordinates stay in AC3D's Y-up frame (TORCS swaps to Z-up when it loads a track).
"""
import os
import sys

NO_TEXTURE = {"(null)", "empty_texture_no_mapping", ""}


def convert(lines):
    out = []
    textures = []
    i = 0
    n = len(lines)
    while i < n:
        line = lines[i].rstrip("\n")
        tok = line.split(None, 1)
        key = tok[0] if tok else ""
        if key == "texture":
            rest = tok[1] if len(tok) > 1 else ""
            if rest.startswith('"'):
                end = rest.index('"', 1)
                name, kind = rest[1:end], rest[end + 1:].strip()
            else:
                parts = rest.split()
                name = parts[0] if parts else ""
                kind = parts[1] if len(parts) > 1 else "base"
            if kind in ("", "base") and name not in NO_TEXTURE:
                out.append('texture "%s"' % name)
                if name not in textures:
                    textures.append(name)
            i += 1
        elif key == "numvert":
            count = int(tok[1])
            out.append(line)
            for j in range(count):
                v = lines[i + 1 + j].split()
                out.append(" ".join(v[:3]))
            i += 1 + count
        elif key == "numsurf":
            count = int(tok[1])
            i += 1
            surfs = []
            for _ in range(count):
                flags = int(lines[i].split()[1], 0)
                mat = lines[i + 1].strip()
                nrefs = int(lines[i + 2].split()[1])
                refs = []
                for j in range(nrefs):
                    r = lines[i + 3 + j].split()
                    refs.append((r[0], r[1] if len(r) > 1 else "0", r[2] if len(r) > 2 else "0"))
                i += 3 + nrefs
                if flags & 0xF == 4:
                    base = flags & ~0xF
                    for k in range(len(refs) - 2):
                        tri = (refs[k], refs[k + 1], refs[k + 2]) if k % 2 == 0 else (refs[k + 1], refs[k], refs[k + 2])
                        if len({r[0] for r in tri}) < 3:
                            continue
                        surfs.append((base, mat, tri))
                else:
                    surfs.append((flags, mat, refs))
            out.append("numsurf %d" % len(surfs))
            for flags, mat, refs in surfs:
                out.append("SURF 0x%x" % flags)
                out.append(mat)
                out.append("refs %d" % len(refs))
                out.extend("%s %s %s" % r for r in refs)
        else:
            out.append(line)
            i += 1
    return out, textures


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    with open(sys.argv[1], encoding="latin-1") as f:
        lines = f.readlines()
    out, textures = convert(lines)
    with open(sys.argv[2], "w", encoding="latin-1") as f:
        f.write("\n".join(out) + "\n")
    dirs = sys.argv[3:]
    if dirs:
        for t in textures:
            where = next((d for d in dirs if os.path.isfile(os.path.join(d, t))), "MISSING")
            print("%s %s" % (t, where))


if __name__ == "__main__":
    main()
