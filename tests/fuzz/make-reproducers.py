#!/usr/bin/env python3
"""Writes the generated seed inputs and reproducers of tests/fuzz/ (issue 22): the hostile inputs
the issue lists, in each fuzz target's input format, so that FuzzReplay.<Target> (CTest) and
scripts/fuzz replay them. Run from the repository root; the files are committed, this script
says how they were made. The model and scenario files derived from real ones are made by hand
(see tests/fuzz/crashes/README.md)."""
import bz2
import os
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)))


def write(rel, data):
    path = os.path.join(ROOT, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'wb') as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# --- CityJSON -------------------------------------------------------------------------------
def city(objects, vertices='[[0,0,0],[10,0,0],[10,10,0],[0,10,0]]'):
    return ('{"type":"CityJSON","version":"1.1","transform":{"scale":[1,1,1],"translate":[0,0,0]},'
            '"CityObjects":{%s},"vertices":%s}' % (objects, vertices))


solid = '"geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[0,1,2,3]]]}]'
n = 100000
write('crashes/cityjson/boundaries-nested-100000-deep.city.json',
      city('"b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":%s}]}'
           % ('[' * n + '0' + ']' * n)))
write('crashes/cityjson/attribute-nested-100000-deep.city.json',
      city('"b":{"type":"Building","attributes":{"a":%s},%s}' % ('[' * n + ']' * n, solid)))
chain = ','.join('"o%d":{"type":"Building"%s%s}' % (
    i, ',"parents":["o%d"]' % (i - 1) if i else '', ',"children":["o%d"]' % (i + 1) if i + 1 < 2000 else '')
    for i in range(2000))
write('crashes/cityjson/parent-chain-of-2000.city.json', city(chain))
# A star polygon {2001/1000}: 2,001 vertices, about two million self-crossings.
import math
k, m = 2001, 1000
pts = [[round(1000 * math.cos(2 * math.pi * i * m / k)), round(1000 * math.sin(2 * math.pi * i * m / k)), 0]
       for i in range(k)]
write('crashes/cityjson/star-polygon-2001-vertices.city.json',
      city('"b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[%s]]}]}'
           % ('[' + ','.join(str(i) for i in range(k)) + ']'), str(pts).replace(' ', '')))
write('crashes/cityjson/string-of-1-mib-and-16-bytes.city.json',
      city('"%s":{"type":"Building",%s}' % ('x' * ((1 << 20) + 16), solid)))

# --- OSM (OsmFuzzer: first byte 0 XML, 1 the fuzzer compresses the rest, 2 the rest is .bz2) --
osm = ('<?xml version="1.0" encoding="UTF-8"?>\n<osm version="0.6">\n'
       '<node id="1" lat="48.0000" lon="11.0000"/><node id="2" lat="48.0001" lon="11.0000"/>'
       '<node id="3" lat="48.0001" lon="11.0001"/><node id="4" lat="48.0000" lon="11.0001"/>\n'
       '<way id="10"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="1"/>'
       '<tag k="building" v="yes"/><tag k="building:levels" v="1e308"/></way>\n'
       '<way id="11"><nd ref="1"/><nd ref="3"/><tag k="highway" v="residential"/>'
       '<tag k="width" v="1e300"/></way>\n'
       '<way id="12"><nd ref="2"/><nd ref="4"/><tag k="highway" v="primary"/>'
       '<tag k="height" v="inf"/><tag k="width" v="nan"/></way>\n</osm>\n')
write('crashes/osm/absurd-levels-and-widths.osmfuzz', b'\x00' + osm.encode())
# 1.7 kB of bzip2 that inflates to 2 GiB of spaces: the reader must stop at max-inflated.
bomb = bz2.BZ2Compressor(9)
out = [bomb.compress(b'<?xml version="1.0"?>\n<osm version="0.6">')]
block = b' ' * (1 << 20)
for _ in range(2048):
    out.append(bomb.compress(block))
out.append(bomb.flush())
write('crashes/osm/bzip2-bomb-inflating-to-2-gib.osmfuzz', b'\x02' + b''.join(out))

# --- .loa files (LoaFileFuzzer: beside city.osgb and rules.osgt) ----------------------------
write('corpus/loa/city.loa', '{"models": ["city.osgb"], "scenario": "route"}')
write('corpus/loa/city-rules.loa',
      '{"models": ["city.osgb"], "rules": "rules.osgt", "options": "max-depth=10", '
      '"description": "the city with the default rules"}')
write('corpus/loa/pseudo-loader.loa', '{"models": ["city.osgb.loa"], "scenario": "distance"}')
write('crashes/loa/names-itself.loa', '{"models": ["input.loa"]}')
write('crashes/loa/pseudo-loader-chain-of-4000.loa', '{"models": ["city.osgb%s"]}' % ('.loa' * 4000))
write('crashes/loa/json-nested-100000-deep.loa', '{"models": %s}' % ('[' * n + ']' * n))
write('crashes/loa/dev-zero-as-model.loa', '{"models": ["/dev/zero"]}')
write('crashes/loa/itself-through-the-pseudo-loader.loa', '{"models": ["input.loa.loa"]}')

# --- OsmSceneFuzzer (text; see its header) ---------------------------------------------------
write('corpus/osmscene/town.txt',
      'area\nbuilding=yes\nbuilding:levels=3\n11.0 48.0 11.0002 48.0 11.0002 48.0002 11.0 48.0002 11.0 48.0\n'
      'area\nleisure=park\n11.001 48.0 11.002 48.0 11.002 48.001 11.001 48.001 11.001 48.0\n'
      'ring\n11.0013 48.0003 11.0016 48.0003 11.0016 48.0006 11.0013 48.0003\n'
      'way\nhighway=residential\nname=Main Street\n11.0 47.9995 11.002 47.9995 11.003 48.0005\n'
      'way\nwaterway=river\n10.999 48.002 11.003 48.0025\n'
      'node\nnatural=tree\n11.0005 48.0005\n'
      'area\nnatural=water\n11.0025 48.0 11.003 48.0 11.003 48.0004 11.0025 48.0\n')
write('crashes/osmscene/non-finite-coordinates.txt',
      'area\nbuilding=yes\n11.0 48.0 inf 48.0 11.0002 nan 11.0 48.0002 11.0 48.0\n'
      'way\nhighway=primary\n1e308 48.0 -1e308 48.0\nnode\nnatural=tree\nnan nan\n')
write('crashes/osmscene/absurd-tags.txt',
      'area\nbuilding=yes\nheight=1e308\nmin_height=inf\nbuilding:levels=-5\n'
      '11.0 48.0 11.0002 48.0 11.0002 48.0002 11.0 48.0\n'
      'way\nhighway=residential\nwidth=1e300\n11.0 48.0 11.001 48.0\n'
      'node\nnatural=tree\nheight=nan\ndiameter_crown=1e300\n11.0005 48.0005\n')

# --- FilterCacheFuzzer: a valid .loafc (2x2 RGBA8 pyramid) and damaged ones ------------------
def loafc(levels, key=(0x0123456789abcdef, 0xfedcba9876543210), payload=None):
    body = b'osgLoAFC' + struct.pack('<II', 1, len(levels)) + struct.pack('<QQ', *key)
    body += b''.join(struct.pack('<II', w, h) for w, h in levels)
    size = sum(w * h * 4 for w, h in levels)
    body += struct.pack('<Q', size)
    body += payload if payload is not None else bytes((i * 37) & 255 for i in range(size))
    h = 0xcbf29ce484222325
    for c in body:
        h = ((h ^ c) * 0x100000001b3) & 0xffffffffffffffff
    return body + struct.pack('<Q', h)


write('corpus/filtercache/pyramid-2x2.loafc', loafc([(2, 2), (1, 1)]))
write('corpus/filtercache/pyramid-5x3.loafc', loafc([(5, 3), (2, 1), (1, 1)]))
write('crashes/filtercache/levels-claim-65536-squared.loafc', loafc([(65536, 65536), (32768, 32768)], payload=b''))
write('crashes/filtercache/level-count-zero.loafc', loafc([]))
