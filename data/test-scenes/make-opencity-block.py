#!/usr/bin/env python3
"""Writes opencity-block.osgt (beside this script): a 6 x 6 cell city block assembled from
OpenCity's AC3D pieces, which scripts/fetch-test-data extracts from the Debian package
opencity-data into data/cache/opencity-data/PIECE/.

Usage: make-opencity-block.py [OUT.osgt]     (default: opencity-block.osgt beside the script)

The scene:
  - osg::Group "opencity-block", with GL_RESCALE_NORMAL on (the pieces are scaled by 10);
  - per piece an osg::MatrixTransform named after what the piece is (e.g. "building-house-family",
    "road-straight-ns", "tree-pine-2"), holding an osg::ProxyNode with the same name whose
    FileName is "../cache/opencity-data/PIECE/PIECE.ac" (relative to this folder; osgDB loads it
    while reading the .osgt: LOAD_IMMEDIATELY);
  - two pieces written here by hand, because OpenCity has no model for them: the water tile
    ("water-pond", a quad textured with OpenCity's texture/blue_water_512.png) and the ground
    under the block ("terrain-ground", an untextured quad, 5 cm below the pieces).
Frame: OpenCity pieces are Y-up, one cell = 1 unit, spanning x 0..w, z 0..l. Each transform
maps them to Z-up metres: scale 10 (one cell = 10 m, our choice: it makes OpenCity's houses
2.5-7 m tall and its trees 4.5-7 m), rotate +90 degrees about X ((x, y, z) -> (x, -z, y)) and
translate onto the piece's cell, the block centred on the origin: x -30..30 m (column 0..5,
west to east), y 30..-30 m (row 0..5, north to south), z up.
"""
import os
import sys

CELL = 10.0          # metres per OpenCity cell
COLS, ROWS = 6, 6

# (node name, piece folder in data/cache/opencity-data, column, row, width, length)
#   columns run along +x, rows along -y; width along x, length along the rows.
# Roads: column 2 runs north-south, row 3 east-west, crossing at (2, 3).
PIECES = [
    # north-west quarter: houses
    ("building-house-family",        "family",         0, 0, 1, 1),
    ("building-house-little",        "little_house",   1, 0, 1, 1),
    ("building-house-grand-father",  "grand-father",   0, 1, 1, 1),
    ("building-house-easy",          "easybuilding",   1, 1, 1, 1),
    ("building-house-light-of-star", "light-of-star",  0, 2, 1, 1),
    ("building-house-alexandria",    "alexandria",     1, 2, 1, 1),
    # north-east quarter: shops, a hotel, trees
    ("building-hotel",               "hotel",          3, 0, 2, 2),
    ("building-shop-store",          "store",          5, 0, 1, 1),
    ("building-shop-chez-bob",       "chez-bob",       5, 1, 1, 1),
    ("tree-007",                     "tree007",        3, 2, 1, 1),
    ("tree-pine-2",                  "pine2",          4, 2, 1, 1),
    ("tree-fir-1",                   "fir1",           5, 2, 1, 1),
    # south-west quarter: a block of flats
    ("building-flats-charmilles",    "charmilles",     0, 4, 2, 2),
    # south-east quarter: park, pond, house, trees
    ("park",                         "city",           3, 4, 1, 1),
    ("building-house-mep",           "mep",            5, 4, 1, 2),
    ("tree-peking-willow-1",         "peking-willow1", 3, 5, 1, 1),
    ("tree-pine-3",                  "pine3",          4, 5, 1, 1),
]
for row in (0, 1, 2, 4, 5):
    PIECES.append(("road-straight-ns", "road_s_n", 2, row, 1, 1))
for col in (0, 1, 3, 4, 5):
    PIECES.append(("road-straight-we", "road_w_e", col, 3, 1, 1))
PIECES.append(("road-crossing", "road_s_n_w_e", 2, 3, 1, 1))
WATER_CELL = (4, 4)   # "water-pond", written by hand

PIECE_DIR = "../cache/opencity-data"


def cell_matrix(col, row):
    """Row-vector (OSG) matrix: p_world = p_piece * M."""
    s = CELL
    tx = -COLS * CELL / 2 + col * CELL
    ty = ROWS * CELL / 2 - row * CELL
    # (x, y, z) -> (s x + tx, -s z + ty, s y)
    return [[s, 0, 0, 0], [0, 0, s, 0], [0, -s, 0, 0], [tx, ty, 0, 1]]


def fmt(v):
    return ("%.6f" % v).rstrip("0").rstrip(".") if v != int(v) else "%d" % v


class Writer:
    def __init__(self):
        self.lines = []
        self.uid = 0
        self.depth = 0

    def next_id(self):
        self.uid += 1
        return self.uid

    def line(self, text=""):
        self.lines.append("  " * self.depth + text)

    def open(self, text):
        self.line(text + " {")
        self.depth += 1

    def close(self):
        self.depth -= 1
        self.line("}")


def check_layout():
    used = {}
    for name, piece, col, row, w, l in PIECES:
        for c in range(col, col + w):
            for r in range(row, row + l):
                if (c, r) in used or not (0 <= c < COLS and 0 <= r < ROWS):
                    sys.exit("make-opencity-block: cell %d,%d of %s is taken or outside" % (c, r, name))
                used[(c, r)] = name
    if WATER_CELL in used:
        sys.exit("make-opencity-block: the water cell is taken")
    used[WATER_CELL] = "water-pond"
    if len(used) != COLS * ROWS:
        sys.exit("make-opencity-block: %d cells of %d are filled" % (len(used), COLS * ROWS))


def descriptions(w, text):
    w.open("UserDataContainer TRUE")
    w.open("osg::DefaultUserDataContainer")
    w.line("UniqueID %d" % w.next_id())
    w.open("UDC_Descriptions 1")
    w.line('"%s"' % text)
    w.close()
    w.close()
    w.close()


def quad_geode(w, name, corners, normal, texcoords, diffuse, texture):
    w.open("osg::Geode")
    w.line("UniqueID %d" % w.next_id())
    w.line('Name "%s"' % name)
    w.open("StateSet TRUE")
    w.open("osg::StateSet")
    w.line("UniqueID %d" % w.next_id())
    w.open("AttributeList 1")
    w.open("osg::Material")
    w.line("UniqueID %d" % w.next_id())
    w.line('Name "%s"' % name)
    w.line("ColorMode OFF")
    w.line("Ambient TRUE Front 0.2 0.2 0.2 1 Back 0.2 0.2 0.2 1")
    w.line("Diffuse TRUE Front %s 1 Back %s 1" % (diffuse, diffuse))
    w.line("Specular TRUE Front 0 0 0 1 Back 0 0 0 1")
    w.line("Emission TRUE Front 0 0 0 1 Back 0 0 0 1")
    w.line("Shininess TRUE Front 0 Back 0")
    w.close()
    w.line("Value OFF")
    w.close()
    if texture:
        w.open("TextureModeList 1")
        w.open("Data 1")
        w.line("GL_TEXTURE_2D ON")
        w.close()
        w.close()
        w.open("TextureAttributeList 1")
        w.open("Data 1")
        w.open("osg::Texture2D")
        w.line("UniqueID %d" % w.next_id())
        w.line("WRAP_S REPEAT")
        w.line("WRAP_T REPEAT")
        w.line("MIN_FILTER LINEAR_MIPMAP_LINEAR")
        w.line("MAG_FILTER LINEAR")
        w.open("Image TRUE")
        w.line("ClassName osg::Image")
        w.line("UniqueID %d" % w.next_id())
        w.line('FileName "%s"' % texture)
        w.line("WriteHint 0 2")
        w.close()
        w.close()
        w.line("Value OFF")
        w.close()
        w.close()
    w.close()
    w.close()
    w.open("Drawables 1")
    w.open("osg::Geometry")
    w.line("UniqueID %d" % w.next_id())
    w.open("PrimitiveSetList 1")
    w.open("osg::DrawArrays")
    w.line("UniqueID %d" % w.next_id())
    w.line("Mode TRIANGLE_FAN")
    w.line("First 0")
    w.line("Count 4")
    w.close()
    w.close()
    w.open("VertexArray TRUE")
    w.open("osg::Vec3Array")
    w.line("UniqueID %d" % w.next_id())
    w.line("Binding BIND_PER_VERTEX")
    w.open("vector 4")
    for c in corners:
        w.line(" ".join(fmt(v) for v in c))
    w.close()
    w.close()
    w.close()
    w.open("NormalArray TRUE")
    w.open("osg::Vec3Array")
    w.line("UniqueID %d" % w.next_id())
    w.line("Binding BIND_OVERALL")
    w.open("vector 1")
    w.line(" ".join(fmt(v) for v in normal))
    w.close()
    w.close()
    w.close()
    if texcoords:
        w.open("TexCoordArrayList 1")
        w.open("osg::Vec2Array")
        w.line("UniqueID %d" % w.next_id())
        w.line("Binding BIND_PER_VERTEX")
        w.open("vector 4")
        for t in texcoords:
            w.line(" ".join(fmt(v) for v in t))
        w.close()
        w.close()
        w.close()
    w.close()
    w.close()
    w.close()


def main():
    check_layout()
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                             "opencity-block.osgt")
    w = Writer()
    w.line("#Ascii Scene")
    w.line("#Version 161")
    w.line("#Generator make-opencity-block.py 1")  # two words: osgDB reads a name and a version
    w.line("")
    w.open("osg::Group")
    w.line("UniqueID %d" % w.next_id())
    w.line('Name "opencity-block"')
    descriptions(w, "OpenCity (Debian package opencity-data) pieces on a 6x6 grid of 10 m cells; Z up; "
                    "made by data/test-scenes/make-opencity-block.py")
    w.open("StateSet TRUE")
    w.open("osg::StateSet")
    w.line("UniqueID %d" % w.next_id())
    w.open("ModeList 1")
    w.line("GL_RESCALE_NORMAL ON")
    w.close()
    w.close()
    w.close()
    w.open("Children %d" % (len(PIECES) + 2))
    # The ground and the pond, by hand.
    h = COLS * CELL / 2
    quad_geode(w, "terrain-ground", [(-h, -h, -0.05), (h, -h, -0.05), (h, h, -0.05), (-h, h, -0.05)],
               (0, 0, 1), None, "0.45 0.55 0.3", None)
    x0 = -h + WATER_CELL[0] * CELL
    y0 = h - WATER_CELL[1] * CELL
    quad_geode(w, "water-pond", [(x0, y0 - CELL, 0), (x0 + CELL, y0 - CELL, 0), (x0 + CELL, y0, 0), (x0, y0, 0)],
               (0, 0, 1), [(0, 0), (1, 0), (1, 1), (0, 1)], "1 1 1",
               PIECE_DIR + "/texture/blue_water_512.png")
    for name, piece, col, row, width, length in PIECES:
        m = cell_matrix(col, row)
        w.open("osg::MatrixTransform")
        w.line("UniqueID %d" % w.next_id())
        w.line('Name "%s"' % name)
        descriptions(w, "opencity-data piece %s at column %d row %d (%dx%d cells)" % (piece, col, row, width, length))
        w.open("Children 1")
        w.open("osg::ProxyNode")
        w.line("UniqueID %d" % w.next_id())
        w.line('Name "%s"' % name)
        w.open("FileNames 1")
        w.line('"%s/%s/%s.ac"' % (PIECE_DIR, piece, piece))
        w.close()
        w.line("LoadingExternalReferenceMode LOAD_IMMEDIATELY")
        w.close()
        w.close()
        w.open("Matrix")
        for r in m:
            w.line(" ".join(fmt(v) for v in r))
        w.close()
        w.close()
    w.close()
    w.close()
    with open(out, "w") as f:
        f.write("\n".join(w.lines) + "\n")


if __name__ == "__main__":
    main()
