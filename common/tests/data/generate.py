#!/usr/bin/env python3
"""Writes the small mesh files of common/tests/data (valid ones of every format and variant, and one hostile file per
failure class). The outputs are committed; rerun this only to change them:  python3 generate.py
Every file is a few hundred bytes; the expected counts are asserted in common/tests/mesh_io_*_test.cpp."""
import base64
import json
import math
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# A tetrahedron, outward-facing (counter-clockwise seen from outside).
TET_V = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
TET_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def write(name, data):
    mode = 'wb' if isinstance(data, bytes) else 'w'
    with open(os.path.join(HERE, name), mode, newline='' if mode == 'w' else None) as f:
        f.write(data)


# ---------------------------------------------------------------- PLY
def ply_header(fmt, vertex_props, face_props, nv, nf, comments=(), extra=''):
    h = 'ply\nformat %s 1.0\n' % fmt
    for c in comments:
        h += 'comment %s\n' % c
    h += 'element vertex %d\n' % nv
    for t, n in vertex_props:
        h += 'property %s %s\n' % (t, n)
    h += extra
    h += 'element face %d\n' % nf
    for p in face_props:
        h += 'property %s\n' % p
    return h


def valid_ply():
    comments = ['made by generate.py', '  two leading blanks kept']
    # ASCII: extra vertex properties, a face property, an unknown element after the faces, obj_info.
    h = ('ply\nformat ascii 1.0\ncomment made by generate.py\ncomment   two leading blanks kept\nobj_info ignored\n'
         'element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float confidence\n'
         'property uchar red\nelement face 4\nproperty list uchar int vertex_indices\nproperty int relief\n'
         'element material 2\nproperty float shine\nproperty list uchar float tint\nend_header\n')
    body = ''
    for i, v in enumerate(TET_V):
        body += '%g %g %g %g %d\n' % (v + (0.25 * i, 10 * i))
    for i, f in enumerate(TET_F):
        body += '3 %d %d %d %d\n' % (f + (i - 1,))
    body += '0.5 3 1 2 3\n1.5 0\n'
    write('tet_ascii.ply', h + body)

    # Binary little endian, double positions, a short property, the unknown element before the faces.
    h = ('ply\nformat binary_little_endian 1.0\ncomment little endian\nelement vertex 4\nproperty double x\n'
         'property double y\nproperty double z\nproperty short label\nelement junk 3\nproperty int a\n'
         'property list uchar short b\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n')
    b = b''
    for i, v in enumerate(TET_V):
        b += struct.pack('<dddh', *v, -i)
    for i in range(3):
        b += struct.pack('<iB', i, i) + struct.pack('<%dh' % i, *range(i))
    for f in TET_F:
        b += struct.pack('<B3i', 3, *f)
    write('tet_binary_le.ply', h.encode() + b)

    # Binary big endian, float positions, 'vertex_index' with a uint count, CRLF header lines.
    h = ('ply\r\nformat binary_big_endian 1.0\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\n'
         'property float z\r\nelement face 4\r\nproperty list uint uint vertex_index\r\nend_header\r\n')
    b = b''
    for v in TET_V:
        b += struct.pack('>fff', *v)
    for f in TET_F:
        b += struct.pack('>I3I', 3, *f)
    write('tet_binary_be.ply', h.encode() + b)

    # Triangle strips (as igea.ply): a 4 x 2 grid of vertices, one run of 6 indices, -1, a second run of 4.
    # Run 1: 0 4 1 5 2 6 -> 4 triangles; run 2 (restarts parity): 2 6 3 7 -> 2 triangles. Triangle k of a run is
    # (s[k], s[k+1], s[k+2]) for even k and (s[k+1], s[k], s[k+2]) for odd k.
    verts = [(x, y, 0.0) for y in (0, 1) for x in (0, 1, 2, 3)]
    strip = [0, 4, 1, 5, 2, 6, -1, 2, 6, 3, 7, 7]  # the last index repeats: a degenerate triangle, skipped
    h = ('ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n'
         'property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n')
    b = b''.join(struct.pack('<fff', *v) for v in verts)
    b += struct.pack('<i', len(strip)) + b''.join(struct.pack('<i', s) for s in strip)
    write('strips.ply', h.encode() + b)

    # Polygons: a quad and a pentagon in ASCII.
    h = ('ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\nproperty float z\n'
         'element face 2\nproperty list uchar int vertex_indices\nend_header\n')
    body = '0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n3 1 0\n2 2 0\n4 0 1 2 3\n5 1 4 5 6 2\n'
    write('polygons.ply', h + body)


def hostile_ply():
    hdr = ('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
           'property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n')
    good_v = b''.join(struct.pack('<fff', *v) for v in TET_V)
    good_f = b''.join(struct.pack('<B3i', 3, *f) for f in TET_F)
    full = (hdr % (4, 4)).encode() + good_v + good_f
    write('hostile_truncated_binary.ply', full[:-7])
    write('hostile_count_mismatch.ply', (hdr % (4, 10)).encode() + good_v + good_f)
    write('hostile_billions.ply', (hdr % (4000000000, 4)).encode() + good_v + good_f)
    write('hostile_billions_fits.ply', (hdr % (4, 2000000000)).encode() + good_v + good_f)
    nan_v = struct.pack('<fff', float('nan'), 0, 0) + good_v[12:]
    write('hostile_nan.ply', (hdr % (4, 4)).encode() + nan_v + good_f)
    bad_f = good_f[:-4] + struct.pack('<i', 9)
    write('hostile_index.ply', (hdr % (4, 4)).encode() + good_v + bad_f)
    neg_f = good_f[:-4] + struct.pack('<i', -2)
    write('hostile_negative_index.ply', (hdr % (4, 4)).encode() + good_v + neg_f)
    write('hostile_negative_count.ply', (hdr % (-4, 4)).encode() + good_v + good_f)
    # A list count claiming 200 entries in a 4-face file.
    big_list = struct.pack('<B3i', 200, 0, 1, 2) + good_f[13:]
    write('hostile_list_count.ply', (hdr % (4, 4)).encode() + good_v + big_list)
    # ASCII: the last face line is missing.
    a = ('ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n'
         'element face 4\nproperty list uchar int vertex_indices\nend_header\n')
    a += ''.join('%g %g %g\n' % v for v in TET_V) + ''.join('3 %d %d %d\n' % f for f in TET_F[:3])
    write('hostile_truncated_ascii.ply', a)
    write('hostile_no_end_header.ply', 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n')
    write('hostile_empty.ply', b'')


# ---------------------------------------------------------------- OBJ
def valid_obj():
    cube_v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    quads = [(1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4)]
    s = '# a unit cube of quads\n# second comment\n'
    s += ''.join('v %g %g %g\n' % v for v in cube_v)
    s += ''.join('f %d %d %d %d\n' % q for q in quads)
    write('cube_quads.obj', s)

    # Relative indices: each face refers back to the vertices just listed.
    s = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -1 -2\nv 0 0 1\nf -4 -3 -1\nf 1 4 3\nf 2 3 4\n'
    write('negative_indices.obj', s)

    # The v/vt/vn corner forms, objects, groups, materials, smoothing, a vertex colour and a comment at the end of a line.
    s = ('mtllib missing.mtl\no tet\ng side\nv 0 0 0\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nv 0 0 1 # apex\n'
         'vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 -1\nvn 0 -1 0\nvn -1 0 0\nvn 1 1 1\nusemtl m\ns 1\n'
         'f 1/1/1 3/3/1 2/2/1\nf 1//2 2//2 4//2\ng other\nf 1/1 4/2 3/3\nf 2/1/4 3/2/4 4/3/4\n')
    write('corner_forms.obj', s)

    # An L-shaped (concave) hexagon in the z = 0 plane; area 3.
    s = 'v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n'
    write('concave.obj', s)


def hostile_obj():
    tri = 'v 0 0 0\nv 1 0 0\nv 0 1 0\n'
    write('hostile_nan.obj', 'v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n')
    write('hostile_inf.obj', 'v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n')
    write('hostile_not_a_number.obj', 'v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n')
    write('hostile_two_coordinates.obj', 'v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n')
    write('hostile_index.obj', tri + 'f 1 2 4\n')
    write('hostile_index_zero.obj', tri + 'f 0 1 2\n')
    write('hostile_index_overflow.obj', tri + 'f 1 2 4294967297\n')
    write('hostile_relative_index.obj', tri + 'f -1 -2 -4\n')
    write('hostile_two_corners.obj', tri + 'f 1 2\n')
    write('hostile_no_faces.obj', tri)
    write('hostile_empty.obj', b'')


# ---------------------------------------------------------------- OFF
def off_body(v, f):
    return ''.join('%g %g %g\n' % p for p in v) + ''.join('3 %d %d %d\n' % t for t in f)


def valid_off():
    write('tet.off', 'OFF\n4 4 6\n' + off_body(TET_V, TET_F))
    # Counts on the keyword line, comments, blank lines.
    write('tet_counts_on_keyword_line.off', '# comment before\nOFF 4 4 0\n\n# vertices\n' + off_body(TET_V, TET_F))
    # NOFF: a normal after each position.
    s = 'NOFF\n4 4 0\n' + ''.join('%g %g %g 0 0 1\n' % p for p in TET_V) + ''.join('3 %d %d %d\n' % t for t in TET_F)
    write('tet_noff.off', s)
    # COFF: a colour after each position, and per-face colours.
    s = 'COFF\n4 4 0\n' + ''.join('%g %g %g 255 0 0 255\n' % p for p in TET_V)
    s += ''.join('3 %d %d %d 0.5 0.5 0.5\n' % t for t in TET_F)
    write('tet_coff.off', s)
    # Two unreferenced vertices, a face with a repeated vertex, a quad.
    v = TET_V + [(5, 5, 5), (6, 6, 6)]
    s = 'OFF\n6 6 0\n' + ''.join('%g %g %g\n' % p for p in v) + ''.join('3 %d %d %d\n' % t for t in TET_F)
    s += '3 0 0 1\n4 0 1 2 2\n'
    write('unreferenced.off', s)
    # Three triangles on edge (0, 1): repair refuses it.
    write('nonmanifold_edge.off', 'OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n')
    # A unit cube of quads without its top: one hole of four edges.
    cube_v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2)]
    write('open_box.off', 'OFF\n8 5 0\n' + ''.join('%g %g %g\n' % v for v in cube_v) +
          ''.join('4 %d %d %d %d\n' % q for q in quads))


def hostile_off():
    write('hostile_truncated.off', 'OFF\n4 4 0\n' + off_body(TET_V, TET_F)[:-8])
    # The header says 5 vertices; there are 4, so a face line is read as a vertex and the faces run out.
    write('hostile_count_mismatch.off', 'OFF\n5 4 0\n' + off_body(TET_V, TET_F))
    write('hostile_inf.off', 'OFF\n4 4 0\n0 0 0\ninf 0 0\n0 1 0\n0 0 1\n' + ''.join('3 %d %d %d\n' % t for t in TET_F))
    write('hostile_index.off', 'OFF\n4 4 0\n' + off_body(TET_V, TET_F[:3] + [(1, 2, 7)]))
    write('hostile_negative_count.off', 'OFF\n-4 4 0\n' + off_body(TET_V, TET_F))
    write('hostile_billions.off', 'OFF\n2000000000 2000000000 0\n' + off_body(TET_V, TET_F))
    write('hostile_not_off.off', 'COFFEE\n4 4 0\n' + off_body(TET_V, TET_F))
    write('hostile_empty.off', b'')


# ---------------------------------------------------------------- STL
def stl_ascii(tris, name='tet'):
    s = 'solid %s\n' % name
    for t in tris:
        s += '  facet normal 0 0 0\n    outer loop\n'
        for p in t:
            s += '      vertex %r %r %r\n' % p
        s += '    endloop\n  endfacet\n'
    return s + 'endsolid %s\n' % name


def stl_binary(tris, header=b'binary tet', count=None):
    b = header.ljust(80, b'\0')[:80] + struct.pack('<I', len(tris) if count is None else count)
    for t in tris:
        b += struct.pack('<3f', 0, 0, 0) + b''.join(struct.pack('<3f', *p) for p in t) + b'\0\0'
    return b


def valid_stl():
    tris = [tuple(TET_V[i] for i in f) for f in TET_F]
    write('tet_ascii.stl', stl_ascii(tris))
    write('tet_binary.stl', stl_binary(tris))
    write('tet_binary_solid_header.stl', stl_binary(tris, header=b'solid but binary'))
    # Two triangles whose shared corners differ by 1e-6: welded only with a tolerance.
    t1 = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    t2 = ((1.000001, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.000001, 0.0))
    write('near_coincident.stl', stl_ascii([t1, t2], 'near'))


def hostile_stl():
    tris = [tuple(TET_V[i] for i in f) for f in TET_F]
    write('hostile_truncated_binary.stl', stl_binary(tris)[:-20])
    write('hostile_count_mismatch.stl', stl_binary(tris, count=5))
    write('hostile_billions.stl', stl_binary(tris, count=0xFFFFFFFF))
    write('hostile_truncated_solid_header.stl', stl_binary(tris, header=b'solid but binary')[:-20])
    write('hostile_truncated_ascii.stl', stl_ascii(tris)[:-60])
    bad = [((0.0, 0.0, 0.0), (float('nan'), 0.0, 0.0), (0.0, 1.0, 0.0))]
    write('hostile_nan.stl', stl_ascii(bad))
    write('hostile_four_vertices.stl', 'solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n'
          'vertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid x\n')
    write('hostile_empty.stl', b'')


# ---------------------------------------------------------------- glTF / GLB
def gltf_model(positions, indices, index_type=5123, nodes=None, count_override=None):
    pos = b''.join(struct.pack('<3f', *p) for p in positions)
    fmt = {5121: 'B', 5123: 'H', 5125: 'I'}[index_type]
    idx = b''.join(struct.pack('<' + fmt, i) for i in indices)
    while len(idx) % 4:
        idx += b'\0'
    buf = pos + idx
    lo = [min(p[a] for p in positions if not math.isnan(p[a])) for a in range(3)]  # JSON has no NaN
    hi = [max(p[a] for p in positions if not math.isnan(p[a])) for a in range(3)]
    model = {
        'asset': {'version': '2.0', 'generator': 'generate.py'},
        'scene': 0,
        'scenes': [{'nodes': [0]}],
        'nodes': nodes or [{'mesh': 0}],
        'meshes': [{'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1, 'mode': 4},
                                   {'attributes': {'POSITION': 0}, 'mode': 1}]}],  # lines: skipped
        'buffers': [{'byteLength': len(buf)}],
        'bufferViews': [{'buffer': 0, 'byteOffset': 0, 'byteLength': len(pos)},
                        {'buffer': 0, 'byteOffset': len(pos), 'byteLength': len(idx)}],
        'accessors': [{'bufferView': 0, 'componentType': 5126, 'type': 'VEC3', 'count': len(positions),
                       'min': lo, 'max': hi},
                      {'bufferView': 1, 'componentType': index_type, 'type': 'SCALAR',
                       'count': len(indices) if count_override is None else count_override}],
    }
    return model, buf


def glb(model, buf):
    js = json.dumps(model, separators=(',', ':')).encode()
    while len(js) % 4:
        js += b' '
    while len(buf) % 4:
        buf += b'\0'
    body = struct.pack('<II', len(js), 0x4E4F534A) + js + struct.pack('<II', len(buf), 0x004E4942) + buf
    return struct.pack('<III', 0x46546C67, 2, 12 + len(body)) + body


def valid_gltf():
    flat = [i for f in TET_F for i in f]
    # .gltf with the buffer in a data URI, placed by a parent node (translation) and a child (uniform scale 2).
    model, buf = gltf_model(TET_V, flat, nodes=[{'children': [1], 'translation': [10, 0, 0]},
                                                 {'mesh': 0, 'scale': [2, 2, 2]}])
    model['buffers'][0]['uri'] = 'data:application/octet-stream;base64,' + base64.b64encode(buf).decode()
    write('tet_transformed.gltf', json.dumps(model, indent=1) + '\n')
    # .gltf with its buffer in a file beside it.
    model, buf = gltf_model(TET_V, flat)
    model['buffers'][0]['uri'] = 'tet_external.bin'
    write('tet_external.gltf', json.dumps(model, indent=1) + '\n')
    write('tet_external.bin', buf)
    # .glb, uint32 indices, no node transform; the same mesh placed twice by two nodes (a mirror flips the faces).
    model, buf = gltf_model(TET_V, flat, index_type=5125)
    write('tet.glb', glb(model, buf))
    model, buf = gltf_model(TET_V, flat, index_type=5121,
                            nodes=[{'children': [1, 2]}, {'mesh': 0},
                                   {'mesh': 0, 'scale': [-1, 1, 1], 'translation': [5, 0, 0]}])
    write('tet_instanced.glb', glb(model, buf))


def hostile_gltf():
    flat = [i for f in TET_F for i in f]
    model, buf = gltf_model(TET_V, flat[:-1] + [9])
    write('hostile_index.glb', glb(model, buf))
    model, buf = gltf_model(TET_V, flat, count_override=1 << 40)
    write('hostile_billions.glb', glb(model, buf))
    model, buf = gltf_model(TET_V, flat)
    write('hostile_truncated.glb', glb(model, buf)[:-30])
    nan_v = [(float('nan'), 0.0, 0.0)] + TET_V[1:]
    model, buf = gltf_model(nan_v, flat)
    write('hostile_nan.glb', glb(model, buf))
    write('hostile_empty.glb', b'')
    model, buf = gltf_model(TET_V, flat)
    # A device must not be read (it, or a FIFO, could block or never end); enough '..' to reach / from anywhere.
    model['buffers'][0]['uri'] = '../' * 40 + 'dev/zero'
    write('hostile_device_buffer.gltf', json.dumps(model, indent=1) + '\n')
    write('hostile_not_json.gltf', '{"asset": {"version": "2.0"}, "meshes": [ {"primitives": [\n')


def garbage():
    rng = random.Random(20261122)
    for ext in ('ply', 'obj', 'off', 'stl', 'glb'):
        write('hostile_garbage.' + ext, bytes(rng.randrange(256) for _ in range(1000)))


if __name__ == '__main__':
    valid_ply()
    hostile_ply()
    valid_obj()
    hostile_obj()
    valid_off()
    hostile_off()
    valid_stl()
    hostile_stl()
    valid_gltf()
    hostile_gltf()
    garbage()
