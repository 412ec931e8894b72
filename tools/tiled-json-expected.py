#!/usr/bin/env python3
"""What Tiled's own JSON export of a map says, as Scheme data, for the tests.

    cd tests && python3 ../tools/tiled-json-expected.py EXPORT.tmj ...

Tiled (`tiled --export-map json in.tmx out.tmj`) writes the map as it read
it; this prints, for every export given, one datum that tests/tmj-test.scm
compares field by field with what our TMX loader makes of in.tmx:

  ("EXPORT.tmj"
   (map (KEY VALUE) ...)
   (properties (NAME TYPE VALUE) ...)
   (tilesets ((KEY VALUE) ...) ...)
   (layers ((KEY VALUE) ...) ...))

Layers come in document order, a group before its children, with the
effective values the loader computes (offsets added, parallax and opacity
multiplied, visibility and-ed through groups). A tile layer's `cells` are
its non-empty cells as (COL ROW RAW-VALUE), row by row, in Tiled's
coordinates (chunk positions for infinite maps). An object is the keys its
JSON has (a template instance has only what it overrides). Colours are
(R G B A); file paths are resolved against the export's directory and
written relative to the current directory. Properties are sorted by name,
as Tiled saves them. Only python's standard library is used (json, base64,
zlib, gzip; zstd through the zstd program), never the Scheme loader.
"""
import base64, gzip, json, os, struct, subprocess, sys, zlib


def q(s):
    return '"' + s.replace('\\', '\\\\').replace('"', '\\"').replace('\n', '\\n') + '"'


def sx(v):
    """A Python value as Scheme text."""
    if v is True:
        return '#t'
    if v is False:
        return '#f'
    if v is None:
        return '#f'
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, str):
        return q(v)
    if isinstance(v, Sym):
        return v.name
    return '(' + ' '.join(sx(x) for x in v) + ')'


class Sym:
    def __init__(self, name):
        self.name = name


def color(s):
    if not s:
        return None
    s = s.lstrip('#')
    if len(s) == 6:
        return [int(s[0:2], 16), int(s[2:4], 16), int(s[4:6], 16), 255]
    return [int(s[2:4], 16), int(s[4:6], 16), int(s[6:8], 16), int(s[0:2], 16)]


def path_of(base, p):
    if p == '':
        return ''
    return os.path.normpath(os.path.relpath(os.path.join(base, p)))


def prop_value(base, t, v):
    if t == 'float':
        return float(v)
    if t == 'color':
        return color(v) or []
    if t == 'file':
        return path_of(base, v)
    if t == 'class':
        return [[k, member(v[k])] for k in sorted(v)]
    return v


def member(v):
    if isinstance(v, dict):
        return [[k, member(v[k])] for k in sorted(v)]
    return v


def properties(base, node):
    ps = node.get('properties', [])
    return [[p['name'], Sym(p.get('type', 'string')),
             prop_value(base, p.get('type', 'string'), p.get('value'))]
            for p in sorted(ps, key=lambda p: p['name'])]


def decode(d, layer, w, h):
    if isinstance(d, list):
        gids = d
    else:
        raw = base64.b64decode(d)
        comp = layer.get('compression', '')
        if comp == 'zlib':
            raw = zlib.decompress(raw)
        elif comp == 'gzip':
            raw = gzip.decompress(raw)
        elif comp == 'zstd':
            raw = subprocess.run(['zstd', '-d', '-c'], input=raw, capture_output=True,
                                 check=True).stdout
        gids = list(struct.unpack('<%dI' % (len(raw) // 4), raw))
    assert len(gids) == w * h, (len(gids), w, h)
    return gids


def cells(layer):
    out = []
    if 'chunks' in layer:
        for ch in layer['chunks']:
            x, y, w, h = ch['x'], ch['y'], ch['width'], ch['height']
            for i, g in enumerate(decode(ch['data'], layer, w, h)):
                if g:
                    out.append((x + i % w, y + i // w, g))
    else:
        w, h = layer['width'], layer['height']
        for i, g in enumerate(decode(layer['data'], layer, w, h)):
            if g:
                out.append((i % w, i // w, g))
    out.sort(key=lambda c: (c[1], c[0]))
    return [list(c) for c in out]


OBJECT_KEYS = ['id', 'name', 'type', 'x', 'y', 'width', 'height', 'rotation', 'gid', 'visible']
TEXT_KEYS = ['text', 'fontfamily', 'pixelsize', 'wrap', 'color', 'bold', 'italic', 'underline',
             'strikeout', 'kerning', 'halign', 'valign']


def obj(base, o):
    out = [[k, o[k]] for k in OBJECT_KEYS if k in o]
    shape = None
    for s in ('ellipse', 'point', 'capsule'):
        if o.get(s):
            shape = s
    for s in ('polygon', 'polyline'):
        if s in o:
            shape = s
            out.append(['points', [[p['x'], p['y']] for p in o[s]]])
    if 'text' in o:
        shape = 'text'
        t = o['text']
        out.append(['text', [[k, color(t[k]) if k == 'color' else t[k]] for k in TEXT_KEYS if k in t]])
    if shape is None and 'template' not in o:
        shape = 'tile' if o.get('gid', 0) & 0x0FFFFFFF else 'rectangle'
    if shape:
        out.append(['shape', Sym(shape)])
    if 'template' in o:
        out.append(['template', path_of(base, o['template'])])
    if 'properties' in o:
        out.append(['properties', properties(base, o)])
    return out


def layers(base, nodes, inh, acc):
    ox, oy, px, py, op, vis = inh
    for l in nodes:
        e = (ox + l.get('offsetx', 0), oy + l.get('offsety', 0),
             px * l.get('parallaxx', 1), py * l.get('parallaxy', 1),
             op * l.get('opacity', 1), vis and l.get('visible', True))
        kind = {'tilelayer': 'tile', 'objectgroup': 'object', 'imagelayer': 'image',
                'group': 'group'}[l['type']]
        out = [['kind', Sym(kind)], ['name', l.get('name', '')], ['id', l.get('id')],
               ['offset', [e[0], e[1]]], ['parallax', [e[2], e[3]]], ['opacity', e[4]],
               ['visible', e[5]], ['locked', l.get('locked', False)],
               ['tint', color(l.get('tintcolor'))], ['properties', properties(base, l)]]
        if kind == 'tile':
            out.append(['cells', cells(l)])
        elif kind == 'object':
            out.append(['color', color(l.get('color'))])
            out.append(['draworder', Sym(l.get('draworder', 'topdown'))])
            out.append(['objects', [obj(base, o) for o in l.get('objects', [])]])
        elif kind == 'image':
            out.append(['image', path_of(base, l['image']) if l.get('image') else False])
            out.append(['repeat', [l.get('repeatx', False), l.get('repeaty', False)]])
        acc.append(out)
        if kind == 'group':
            layers(base, l.get('layers', []), e, acc)
    return acc


def tileset(base, t):
    if 'source' in t:
        return [['firstgid', t['firstgid']], ['source', path_of(base, t['source'])]]
    out = [['firstgid', t['firstgid']]] + [[k, t[k]] for k in
                                           ('name', 'tilewidth', 'tileheight', 'spacing', 'margin',
                                            'tilecount', 'columns') if k in t]
    if t.get('image'):
        out.append(['image', path_of(base, t['image'])])
    out.append(['properties', properties(base, t)])
    out.append(['tiles', [[['id', tl['id']], ['type', tl.get('type', tl.get('class', ''))],
                           ['properties', properties(base, tl)],
                           ['animation', [[f['tileid'], f['duration']] for f in tl.get('animation', [])]],
                           ['shapes', [obj(base, o) for o in tl.get('objectgroup', {}).get('objects', [])]]]
                          for tl in t.get('tiles', [])]])
    return out


def describe(path):
    d = json.load(open(path))
    base = os.path.dirname(path)
    m = [[k, d[k]] for k in ('orientation', 'renderorder', 'tilewidth', 'tileheight', 'infinite',
                             'hexsidelength', 'staggeraxis', 'staggerindex', 'parallaxoriginx',
                             'parallaxoriginy') if k in d]
    if not d.get('infinite'):
        m += [['width', d['width']], ['height', d['height']]]
    m.append(['backgroundcolor', color(d.get('backgroundcolor'))])
    return '(%s\n (map %s)\n (properties %s)\n (tilesets %s)\n (layers\n  %s))' % (
        q(path), ' '.join(sx(x) for x in m), sx(properties(base, d)),
        ' '.join(sx(tileset(base, t)) for t in d.get('tilesets', [])),
        '\n  '.join(sx(l) for l in layers(base, d.get('layers', []), (0, 0, 1, 1, 1, True), [])))


if __name__ == '__main__':
    for p in sys.argv[1:]:
        print(describe(p))
