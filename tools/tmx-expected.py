#!/usr/bin/env python3
"""Expected values for the TMX tests, computed without the Scheme loader.

    python3 tools/tmx-expected.py tests/data/tiled-examples [more.tmx ...]

For every .tmx file found it prints one Scheme datum:

  ("relative/path.tmx" LAYER-COUNT TILE-LAYER-COUNT OBJECT-COUNT
    (("layer name" NON-EMPTY FLIPPED ((COL ROW RAW-GID) ...)) ...))

LAYER-COUNT counts every layer (tile, object, image, group; those inside
groups too); OBJECT-COUNT the objects of all object layers. Then one entry per tile layer in document order (group contents
included): the cells whose gid, flip bits cleared, is not 0; the cells with
any of the four flag bits set; and up to four sample cells (the first and last
non-empty cell, the first flipped one, and the middle non-empty one), with
their raw 32-bit value. Columns and rows are Tiled's (chunk coordinates for
infinite maps). Only the standard library is used: xml.etree, base64, zlib,
gzip.
"""
import base64, gzip, os, struct, sys, zlib
import xml.etree.ElementTree as ET

FLAGS = 0xF0000000


def decode(data, w, h):
    enc = data.get('encoding')
    comp = data.get('compression')
    if enc is None:
        gids = [int(t.get('gid', '0')) for t in data.findall('tile')]
    elif enc == 'csv':
        gids = [int(x) for x in (data.text or '').replace('\n', '').split(',') if x.strip()]
    elif enc == 'base64':
        raw = base64.b64decode((data.text or '').strip())
        if comp == 'zlib':
            raw = zlib.decompress(raw)
        elif comp == 'gzip':
            raw = gzip.decompress(raw)
        elif comp == 'zstd':
            raise SystemExit('zstd is not in python\'s standard library')
        elif comp:
            raise SystemExit('unknown compression ' + comp)
        gids = list(struct.unpack('<%dI' % (len(raw) // 4), raw))
    else:
        raise SystemExit('unknown encoding ' + enc)
    assert len(gids) == w * h, (len(gids), w, h)
    return gids


def cells(layer):
    """(col, row, raw) of every cell of a tile layer, chunks included."""
    data = layer.find('data')
    out = []
    chunks = data.findall('chunk')
    if chunks:
        for ch in chunks:
            x, y = int(ch.get('x')), int(ch.get('y'))
            w, h = int(ch.get('width')), int(ch.get('height'))
            ch.set('encoding', data.get('encoding') or '')
            if data.get('encoding') is None:
                del ch.attrib['encoding']
            if data.get('compression'):
                ch.set('compression', data.get('compression'))
            for i, g in enumerate(decode(ch, w, h)):
                out.append((x + i % w, y + i // w, g))
    else:
        w, h = int(layer.get('width')), int(layer.get('height'))
        for i, g in enumerate(decode(data, w, h)):
            out.append((i % w, i // w, g))
    return out


def walk(node, acc):
    for child in node:
        if child.tag in ('layer', 'objectgroup', 'imagelayer', 'group'):
            acc.append(child)
            if child.tag == 'group':
                walk(child, acc)
    return acc


def q(s):
    return '"' + s.replace('\\', '\\\\').replace('"', '\\"') + '"'


def describe(path, root_dir):
    root = ET.parse(path).getroot()
    layers = walk(root, [])
    tile_layers = [l for l in layers if l.tag == 'layer']
    parts = []
    for l in tile_layers:
        cs = cells(l)
        full = [c for c in cs if c[2] & ~FLAGS]
        flipped = [c for c in cs if c[2] & FLAGS]
        samples = []
        for c in (full[:1] + full[-1:] + flipped[:1] + full[len(full) // 2:len(full) // 2 + 1]):
            if c not in samples:
                samples.append(c)
        samples.sort(key=lambda c: (c[1], c[0]))
        parts.append('(%s %d %d (%s))' % (q(l.get('name', '')), len(full), len(flipped),
                                          ' '.join('(%d %d %d)' % c for c in samples)))
    objects = sum(len(l.findall('object')) for l in layers if l.tag == 'objectgroup')
    rel = os.path.relpath(path, root_dir)
    return '(%s %d %d %d\n  (%s))' % (q(rel), len(layers), len(tile_layers), objects,
                                       '\n   '.join(parts))


def main(args):
    root_dir = args[0]
    paths = []
    for a in args:
        if os.path.isdir(a):
            for d, _, fs in os.walk(a):
                paths += [os.path.join(d, f) for f in fs if f.endswith('.tmx')]
        elif a.endswith('.tmx'):
            paths.append(a)
        if os.path.isfile(root_dir):
            root_dir = os.path.dirname(root_dir)
    for p in sorted(paths):
        print(describe(p, root_dir))


if __name__ == '__main__':
    main(sys.argv[1:])
