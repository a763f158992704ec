#!/usr/bin/env python3
"""Converts four public research scenes to glTF 2.0 for tripath (scenes/README.md says what each is).

    scenes/veach-bidir.gltf     Scenes/VeachBidir of pgrit/EfficiencyAwareMIS (PLY meshes, SeeSharp JSON)
    scenes/lamp-caustic.gltf    Scenes/LampCaustic of pgrit/MisForCorrelatedBidir (OBJ, SeeSharp JSON)
    scenes/box-light-top.gltf   Scenes/Box/LightTop of pgrit/MisForCorrelatedBidir (OBJ, SeeSharp JSON)
    scenes/water-caustic.gltf   data/example-scenes/water-caustic of tunabrain/tungsten (.wo3, Tungsten JSON)

Usage (Python 3, standard library only), from the repository's root:

    git clone https://github.com/pgrit/EfficiencyAwareMIS src/EfficiencyAwareMIS
    git -C src/EfficiencyAwareMIS checkout 4e0fdc85d143321882a47a33d87d81009eb27a9d
    git clone https://github.com/pgrit/MisForCorrelatedBidir src/MisForCorrelatedBidir
    git -C src/MisForCorrelatedBidir checkout 6ba56596b3966e68ccbffe6695b501c53830bdb9
    git clone https://github.com/tunabrain/tungsten src/tungsten
    git -C src/tungsten checkout 88ea02044dbaf20472a8173b6752460b50c096d8
    scripts/convert-literature-scenes.py --efficiency-aware-mis src/EfficiencyAwareMIS \
        --mis-for-correlated-bidir src/MisForCorrelatedBidir --tungsten src/tungsten --out scenes

(any folder holding the files of those commits will do; the clones need not live in src/). Each
scene is one .gltf with its buffer embedded as base64, its meshes baked into world space. What each
source construct becomes (materials, emitters, cameras) is written down in scenes/README.md; the
functions below say the same at the place where it happens.

The SeeSharp scenes follow SeeSharp 1.4 (the version both pgrit repositories build on): a transform
is scale, then rotation (yaw about y, pitch about x, roll about z, System.Numerics'
CreateFromYawPitchRoll), then translation, or a 4x4 "matrix" in System.Numerics' row-vector layout
(which, read in order, is glTF's column-major layout); the camera looks along its -z with +y up and
a vertical field of view, as glTF's does. Tungsten's camera has a horizontal field of view.
"""
import argparse
import base64
import json
import math
import os
import struct
import sys
from array import array


def fail(message):
    sys.exit("convert-literature-scenes: " + message)


# ---- small vector and matrix helpers (3-vectors as tuples, 4x4 matrices as row lists) ----

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    length = math.sqrt(dot(a, a))
    return (a[0] / length, a[1] / length, a[2] / length) if length > 0 else (0.0, 0.0, 0.0)


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def identity():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def rotation(axis, degrees):
    """Right-handed rotation about axis 0 (x), 1 (y) or 2 (z), column-vector convention."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = identity()
    m[i][i], m[i][j], m[j][i], m[j][j] = c, -s, s, c
    return m


def scaling(s):
    return [[s[0], 0, 0, 0], [0, s[1], 0, 0], [0, 0, s[2], 0], [0, 0, 0, 1]]


def translation(t):
    return [[1, 0, 0, t[0]], [0, 1, 0, t[1]], [0, 0, 1, t[2]], [0, 0, 0, 1]]


def transform_point(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))


def cofactors(m):
    a = [row[:3] for row in m[:3]]
    return [[a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3]
             - a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3] for j in range(3)] for i in range(3)]


def determinant(m):
    return sum(m[0][j] * cofactors(m)[0][j] for j in range(3))


def normal_matrix(m):
    """The inverse transpose of m's upper 3x3, up to a positive factor (its cofactor matrix)."""
    sign = 1 if determinant(m) > 0 else -1
    return [[sign * c for c in row] for row in cofactors(m)]


def transform_normal(n, p):
    return normalize(tuple(n[i][0] * p[0] + n[i][1] * p[1] + n[i][2] * p[2] for i in range(3)))


def column_major(m):
    return [float(m[i][j]) for j in range(4) for i in range(4)]


def look_at(position, target, up):
    """A camera-to-world matrix looking from position at target: glTF's camera looks along -z."""
    forward = normalize(sub(target, position))
    right = normalize(cross(forward, up))
    true_up = cross(right, forward)
    return [[right[i], true_up[i], -forward[i], position[i]] for i in range(3)] + [[0, 0, 0, 1]]


# ---- meshes ----

class Mesh:
    """A triangle mesh in world space: positions, optional per-vertex normals, triangle indices."""

    def __init__(self, name, positions, normals, triangles):
        self.name, self.positions, self.normals, self.triangles = name, positions, normals, triangles

    def transformed(self, m):
        nm = normal_matrix(m)
        normals = [transform_normal(nm, n) for n in self.normals] if self.normals else None
        triangles = self.triangles
        if determinant(m) < 0:  # mirroring: keep the front faces
            triangles = [(a, c, b) for a, b, c in triangles]
        return Mesh(self.name, [transform_point(m, p) for p in self.positions], normals, triangles)

    def face_normal(self, t):
        p = self.positions
        return cross(sub(p[t[1]], p[t[0]]), sub(p[t[2]], p[t[0]]))

    def wound_like_normals(self):
        """Turns each triangle so that its winding's normal (glTF's front face, tripath's emitting
        side) agrees with its vertex normals, which is what SeeSharp and Tungsten shade and emit by.
        Returns the mesh and how many triangles were turned."""
        if not self.normals:
            return self, 0
        turned = []
        for t in self.triangles:
            mean = [sum(self.normals[v][i] for v in t) for i in range(3)]
            turned.append((t[0], t[2], t[1]) if dot(self.face_normal(t), mean) < 0 else t)
        count = sum(1 for a, b in zip(turned, self.triangles) if a != b)
        return Mesh(self.name, self.positions, self.normals, turned), count


def fan(polygon):
    return [(polygon[0], polygon[i], polygon[i + 1]) for i in range(1, len(polygon) - 1)]


PLY_TYPES = {'char': 'b', 'int8': 'b', 'uchar': 'B', 'uint8': 'B', 'short': 'h', 'int16': 'h',
             'ushort': 'H', 'uint16': 'H', 'int': 'i', 'int32': 'i', 'uint': 'I', 'uint32': 'I',
             'float': 'f', 'float32': 'f', 'double': 'd', 'float64': 'd'}


def read_ply(path):
    """A PLY file's vertices (x y z, and nx ny nz when present) and faces (fans of triangles), in
    ascii or binary of either byte order."""
    data = open(path, 'rb').read()
    end = data.find(b'end_header')
    if not data.startswith(b'ply') or end < 0:
        fail(f"{path}: not a PLY file")
    body = data.index(b'\n', end) + 1
    elements, fmt = [], None
    for line in data[:end].decode('ascii').splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == 'format':
            fmt = words[1]
        elif words[0] == 'element':
            elements.append((words[1], int(words[2]), []))
        elif words[0] == 'property':
            elements[-1][2].append(words[1:])
    if fmt not in ('ascii', 'binary_little_endian', 'binary_big_endian'):
        fail(f"{path}: unknown PLY format {fmt!r}")
    if fmt == 'ascii':
        tokens, pos = data[body:].split(), 0

        def read(kind):
            nonlocal pos
            pos += 1
            return float(tokens[pos - 1]) if PLY_TYPES[kind] in 'fd' else int(tokens[pos - 1])
    else:
        order, pos = '<' if fmt == 'binary_little_endian' else '>', body

        def read(kind):
            nonlocal pos
            code = order + PLY_TYPES[kind]
            value = struct.unpack_from(code, data, pos)[0]
            pos += struct.calcsize(code)
            return value
    rows = {}
    for name, count, properties in elements:
        rows[name] = []
        for _ in range(count):
            row = {}
            for prop in properties:
                if prop[0] == 'list':
                    row[prop[3]] = [read(prop[2]) for _ in range(read(prop[1]))]
                else:
                    row[prop[1]] = read(prop[0])
            rows[name].append(row)
    vertices = rows.get('vertex', [])
    positions = [(v['x'], v['y'], v['z']) for v in vertices]
    normals = [(v['nx'], v['ny'], v['nz']) for v in vertices] if vertices and 'nx' in vertices[0] else None
    triangles = []
    for face in rows.get('face', []):
        triangles += fan(face.get('vertex_indices', face.get('vertex_index')))
    return Mesh(os.path.basename(path), positions, normals, triangles)


def read_obj(path):
    """An OBJ file's faces grouped by material (usemtl), as one mesh per material; a vertex is a
    (position, normal) pair, as SeeSharp's loader keys them. Texture coordinates are not read."""
    v, vn = [], []
    groups = {}  # material -> (key -> index, positions, normals, triangles)
    material = ''
    for line in open(path, encoding='utf-8', errors='replace'):
        words = line.split()
        if not words:
            continue
        if words[0] == 'v':
            v.append(tuple(float(x) for x in words[1:4]))
        elif words[0] == 'vn':
            vn.append(tuple(float(x) for x in words[1:4]))
        elif words[0] == 'usemtl':
            material = words[1] if len(words) > 1 else ''
        elif words[0] == 'f':
            index, positions, normals, triangles = groups.setdefault(material, ({}, [], [], []))
            corners = []
            for corner in words[1:]:
                parts = corner.split('/')
                p = int(parts[0])
                n = int(parts[2]) if len(parts) > 2 and parts[2] else 0
                key = (p + len(v) + 1 if p < 0 else p, n + len(vn) + 1 if n < 0 else n)
                if key not in index:
                    index[key] = len(positions)
                    positions.append(v[key[0] - 1])
                    normals.append(vn[key[1] - 1] if key[1] else None)
                corners.append(index[key])
            triangles += fan(corners)
    meshes = {}
    for material, (_, positions, normals, triangles) in groups.items():
        mesh = Mesh(material, positions, None, triangles)
        if any(n is not None for n in normals):
            mesh.normals = normals
            for t in triangles:  # a corner without a normal takes its face's
                for c in t:
                    if mesh.normals[c] is None:
                        mesh.normals[c] = normalize(mesh.face_normal(t))
        meshes[material] = mesh
    return meshes


def read_wo3(path):
    """Tungsten's binary mesh (src/core/io/MeshIO.cpp): a uint64 vertex count, the vertices (position,
    normal, uv: 8 float32), a uint64 triangle count, the triangles (3 uint32 indices, an int32
    material), all little-endian."""
    data = open(path, 'rb').read()
    (n,) = struct.unpack_from('<Q', data, 0)
    floats = array('f', data[8:8 + 32 * n])
    (m,) = struct.unpack_from('<Q', data, 8 + 32 * n)
    ints = array('I', data[16 + 32 * n:16 + 32 * n + 16 * m])
    if sys.byteorder != 'little':
        floats.byteswap()
        ints.byteswap()
    if len(data) != 16 + 32 * n + 16 * m:
        fail(f"{path}: {len(data)} bytes, not the {16 + 32 * n + 16 * m} of {n} vertices and {m} triangles")
    positions = [tuple(floats[8 * i:8 * i + 3]) for i in range(n)]
    triangles = [tuple(ints[4 * i:4 * i + 3]) for i in range(m)]
    return Mesh(os.path.basename(path), positions, None, triangles)


def tungsten_smooth_normals(mesh):
    """Tungsten's TriangleMesh::calcSmoothVertexNormals: a vertex used by triangles whose normals
    differ by more than 27 degrees (cos 0.15 pi) from the first one's is split off; each vertex then
    sums the area-weighted normals of the triangles at its position within 27 degrees of its own."""
    split = math.cos(math.pi * 0.15)
    positions, triangles = list(mesh.positions), [list(t) for t in mesh.triangles]
    first = [None] * len(positions)
    at_position = {}
    for i, p in enumerate(positions):
        at_position.setdefault(p, []).append(i)
    for t in triangles:
        n = normalize(cross(sub(positions[t[1]], positions[t[0]]), sub(positions[t[2]], positions[t[0]])))
        n = n if n != (0.0, 0.0, 0.0) else (0.0, 1.0, 0.0)
        for k in range(3):
            if first[t[k]] is None:
                first[t[k]] = n
            elif dot(first[t[k]], n) < split:
                positions.append(positions[t[k]])
                first.append(n)
                t[k] = len(positions) - 1
    sums = [[0.0, 0.0, 0.0] for _ in positions]
    for t in triangles:
        n = cross(sub(positions[t[1]], positions[t[0]]), sub(positions[t[2]], positions[t[0]]))
        unit = normalize(n)
        for k in range(3):
            for j in at_position[positions[t[k]]]:  # split copies are not in at_position, as in Tungsten
                if dot(first[j], unit) >= split:
                    for i in range(3):
                        sums[j][i] += n[i]
    normals = [normalize(tuple(s)) if s != [0.0, 0.0, 0.0] else first[i] for i, s in enumerate(sums)]
    return Mesh(mesh.name, positions, normals, [tuple(t) for t in triangles])


# ---- glTF output ----

class Gltf:
    """Collects meshes, materials and one camera, and writes them as a .gltf with an embedded buffer."""

    def __init__(self, source):
        self.doc = {'asset': {'version': '2.0', 'generator': 'tripath scripts/convert-literature-scenes.py',
                              'extras': {'source': source}},
                    'scene': 0, 'scenes': [{'nodes': []}], 'nodes': [], 'meshes': [], 'materials': [],
                    'accessors': [], 'bufferViews': [], 'buffers': []}
        self.data = bytearray()
        self.extensions = set()
        self.triangle_count = 0

    def material(self, name, base_color, metallic, roughness, ior=None, transmission=None, emission=None):
        """A pbrMetallicRoughness material; ior, transmission and emission add their KHR extensions."""
        m = {'name': name, 'pbrMetallicRoughness': {'baseColorFactor': [float(c) for c in base_color] + [1.0],
                                                    'metallicFactor': float(metallic),
                                                    'roughnessFactor': float(roughness)}}
        extensions = {}
        if ior is not None:
            extensions['KHR_materials_ior'] = {'ior': float(ior)}
        if transmission:
            extensions['KHR_materials_transmission'] = {'transmissionFactor': float(transmission)}
        if emission and max(emission) > 0:
            strength = max(emission)
            m['emissiveFactor'] = [float(c) / strength for c in emission]
            if strength > 1:
                extensions['KHR_materials_emissive_strength'] = {'emissiveStrength': float(strength)}
        if extensions:
            m['extensions'] = extensions
            self.extensions.update(extensions)
        self.doc['materials'].append(m)
        return len(self.doc['materials']) - 1

    def view(self, payload, target):
        self.data += b'\0' * (-len(self.data) % 4)
        self.doc['bufferViews'].append({'buffer': 0, 'byteOffset': len(self.data), 'byteLength': len(payload),
                                        'target': target})
        self.data += payload
        return len(self.doc['bufferViews']) - 1

    def accessor(self, values, kind, component, target, bounds=False):
        width = {'VEC3': 3, 'SCALAR': 1}[kind]
        a = array({5126: 'f', 5125: 'I', 5123: 'H'}[component], values)
        if sys.byteorder != 'little':
            a.byteswap()
        accessor = {'bufferView': self.view(a.tobytes(), target), 'componentType': component,
                    'count': len(values) // width, 'type': kind}
        if bounds:  # glTF requires POSITION's min and max, as float32 values
            f = array('f', values)
            accessor['min'] = [min(f[i::3]) for i in range(3)]
            accessor['max'] = [max(f[i::3]) for i in range(3)]
        self.doc['accessors'].append(accessor)
        return len(self.doc['accessors']) - 1

    def mesh(self, mesh, material):
        attributes = {'POSITION': self.accessor([c for p in mesh.positions for c in p], 'VEC3', 5126, 34962, True)}
        if mesh.normals:
            attributes['NORMAL'] = self.accessor([c for n in mesh.normals for c in n], 'VEC3', 5126, 34962)
        component = 5123 if len(mesh.positions) <= 65535 else 5125
        indices = self.accessor([i for t in mesh.triangles for i in t], 'SCALAR', component, 34963)
        self.doc['meshes'].append({'name': mesh.name, 'primitives': [
            {'attributes': attributes, 'indices': indices, 'material': material}]})
        self.doc['nodes'].append({'name': mesh.name, 'mesh': len(self.doc['meshes']) - 1})
        self.doc['scenes'][0]['nodes'].append(len(self.doc['nodes']) - 1)
        self.triangle_count += len(mesh.triangles)

    def camera(self, camera_to_world, yfov_degrees):
        self.doc['cameras'] = [{'type': 'perspective', 'perspective': {
            'yfov': math.radians(yfov_degrees), 'znear': 0.01}}]
        self.doc['nodes'].append({'name': 'camera', 'camera': 0, 'matrix': column_major(camera_to_world)})
        self.doc['scenes'][0]['nodes'].append(len(self.doc['nodes']) - 1)

    def write(self, path):
        if not self.doc['nodes'] or 'cameras' not in self.doc:
            fail(f"{path}: nothing to write")
        self.doc['buffers'] = [{'byteLength': len(self.data), 'uri': 'data:application/octet-stream;base64,'
                                + base64.b64encode(bytes(self.data)).decode('ascii')}]
        if self.extensions:
            self.doc['extensionsUsed'] = sorted(self.extensions)
        with open(path, 'w') as out:
            json.dump(self.doc, out, separators=(',', ':'))
            out.write('\n')
        print(f"wrote {path}: {self.triangle_count} triangles, {len(self.doc['materials'])} materials, "
              f"{os.path.getsize(path) / 1e6:.2f} MB")


# ---- SeeSharp scenes (pgrit/EfficiencyAwareMIS, pgrit/MisForCorrelatedBidir) ----

def rgb(value):
    v = value['value'] if isinstance(value, dict) else value
    return [float(c) for c in (v if isinstance(v, list) else [v] * 3)]


def seesharp_material(gltf, m, name, emission=None):
    """SeeSharp's materials onto tripath's (scenes/README.md has this mapping as a table):
      "diffuse"                          -> metallic 0, roughness 1 (tripath: Lambertian)
      "generic", specularTransmittance>0 -> KHR_materials_transmission 1 and KHR_materials_ior = IOR
                                            (tripath: smooth glass, tinted by the base colour);
                                            roughness below 0.01 is written as 0
      the same, "thin"                   -> metallic 0, roughness 1 (Lambertian): a sheet without
                                            thickness that transmits diffusely, which tripath cannot
                                            model; as glass, a single sheet would bend light as the
                                            surface of a solid would
      "generic", otherwise               -> base colour, metallic, roughness as they are, and
                                            KHR_materials_ior = IOR (the coat of tripath's plastic)
    Dropped: anisotropic, specularTint, thin and diffuseTransmittance, and the roughness of rough
    glass (tripath's glass is smooth)."""
    color = rgb(m['baseColor'])
    if m.get('type', 'generic') == 'diffuse':
        return gltf.material(name, color, 0, 1, emission=emission)
    roughness, metallic = float(m.get('roughness', 0.5)), float(m.get('metallic', 0.0))
    ior = float(m.get('IOR', 1.45))
    if float(m.get('specularTransmittance', 0.0)) > 0 and m.get('thin', False):
        return gltf.material(name, color, 0, 1, emission=emission)
    if float(m.get('specularTransmittance', 0.0)) > 0:
        return gltf.material(name, color, 0, roughness if roughness >= 0.01 else 0, ior=ior, transmission=1,
                             emission=emission)
    return gltf.material(name, color, metallic, roughness, ior=ior if metallic < 1 else None, emission=emission)


def seesharp_transform(t):
    """A SeeSharp named transform as a column-vector matrix: T * Ry(yaw) * Rx(pitch) * Rz(roll) * S,
    or its "matrix"."""
    if 'matrix' in t:
        m = [float(x) for x in t['matrix']]
        return [[m[4 * j + i] for j in range(4)] for i in range(4)]
    r = t.get('rotation', [0, 0, 0])
    m = matmul(rotation(1, r[1]), matmul(rotation(0, r[0]), rotation(2, r[2])))
    return matmul(translation(t.get('position', [0, 0, 0])), matmul(m, scaling(t.get('scale', [1, 1, 1]))))


def seesharp_camera(gltf, scene):
    transforms = {t['name']: seesharp_transform(t) for t in scene['transforms']}
    camera = scene['cameras'][0]
    gltf.camera(transforms[camera['transform']], float(camera['fov']))


def add_oriented(gltf, mesh, material, label):
    mesh, turned = mesh.wound_like_normals()
    if turned:
        print(f"  {label}: {turned} of {len(mesh.triangles)} triangles turned to face their normals")
    gltf.mesh(mesh, material)


def convert_seesharp_ply(folder, source, out):
    """SeeSharp JSON whose objects are PLY files, each with its material and, for an emitter, its own
    emitted radiance (VeachBidir): an emitter gets a copy of its material with that emission."""
    scene = json.load(open(os.path.join(folder, os.path.basename(folder) + '.json')))
    gltf = Gltf(source)
    materials = {m['name']: m for m in scene['materials']}
    indices = {}
    for obj in scene['objects']:
        if obj['type'] != 'ply':
            fail(f"{folder}: object {obj['name']!r} of type {obj['type']!r} is not read")
        m = materials[obj['material']]
        emission = rgb(obj['emission']) if 'emission' in obj else None
        if emission:
            index = seesharp_material(gltf, m, f"{m['name']} ({obj['name']}, emitter)", emission)
        else:
            index = indices.setdefault(m['name'], None)
            if index is None:
                index = indices[m['name']] = seesharp_material(gltf, m, m['name'])
        mesh = read_ply(os.path.join(folder, obj['relativePath']))
        mesh.name = obj['name']
        add_oriented(gltf, mesh, index, obj['name'])
    seesharp_camera(gltf, scene)
    gltf.write(out)


def convert_seesharp_obj(json_path, source, out):
    """SeeSharp JSON whose one object is an OBJ file: its usemtl names pick the JSON's materials, and
    a material with "emission" makes its meshes emitters. A name the JSON lacks gets SeeSharp's
    stand-in (white generic, roughness 0.5), with a note."""
    scene = json.load(open(json_path))
    gltf = Gltf(source)
    materials = {m['name']: m for m in scene['materials']}
    for obj in scene['objects']:
        if obj['type'] != 'obj':
            fail(f"{json_path}: object {obj['name']!r} of type {obj['type']!r} is not read")
        for name, mesh in read_obj(os.path.join(os.path.dirname(json_path), obj['relativePath'])).items():
            m = materials.get(name)
            if m is None:
                print(f"  material {name!r} is not in the JSON: SeeSharp's stand-in (white, roughness 0.5)")
                m = {'type': 'generic', 'name': name, 'baseColor': [1, 1, 1]}
            emission = rgb(m['emission']) if 'emission' in m else None
            add_oriented(gltf, mesh, seesharp_material(gltf, m, name, emission), name)
    seesharp_camera(gltf, scene)
    gltf.write(out)


# ---- Tungsten scenes (tunabrain/tungsten) ----

def tungsten_transform(t):
    """Tungsten's JSON transform without look_at (src/core/io/JsonPtr.cpp): translation * rotYXZ(rotation
    in degrees) * scale, rotYXZ being Ry * Rx * Rz (Mat4f::rotYXZ)."""
    r = t.get('rotation', [0, 0, 0])
    r = r if isinstance(r, list) else [r] * 3
    s = t.get('scale', [1, 1, 1])
    s = s if isinstance(s, list) else [s] * 3
    m = matmul(rotation(1, r[1]), matmul(rotation(0, r[0]), rotation(2, r[2])))
    return matmul(translation(t.get('position', [0, 0, 0])), matmul(m, scaling(s)))


def tungsten_quad():
    """Tungsten's quad: the unit square in y = 0 facing +y (Quad.cpp: normal = edge1 x edge0)."""
    return Mesh('quad', [(-0.5, 0, -0.5), (0.5, 0, -0.5), (0.5, 0, 0.5), (-0.5, 0, 0.5)], None,
                [(0, 2, 1), (0, 3, 2)])


def tungsten_cube():
    """Tungsten's cube: [-0.5, 0.5]^3, each face wound to face outward."""
    positions, triangles = [], []
    for axis in range(3):
        for sign in (-0.5, 0.5):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            base = len(positions)
            for a, b in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = sign, a, b
                positions.append(tuple(p))
            triangles += [(base, base + 1, base + 2), (base, base + 2, base + 3)] if sign > 0 else \
                [(base, base + 2, base + 1), (base, base + 3, base + 2)]
    return Mesh('cube', positions, None, triangles)


def tungsten_material(gltf, bsdf, name, emission=None):
    """Tungsten's BSDFs onto tripath's: lambert -> metallic 0, roughness 1 (Lambertian); dielectric ->
    KHR_materials_transmission 1, KHR_materials_ior = ior; null (a light's) -> black Lambertian."""
    kind = bsdf['type']
    color = rgb(bsdf.get('albedo', 1))
    if kind == 'lambert':
        return gltf.material(name, color, 0, 1, emission=emission)
    if kind == 'dielectric':
        return gltf.material(name, color, 0, 0, ior=bsdf.get('ior', 1.5), transmission=1, emission=emission)
    if kind == 'null':
        return gltf.material(name, [0, 0, 0], 0, 1, emission=emission)
    fail(f"bsdf {name!r} of type {kind!r} is not read")


def convert_tungsten(folder, source, out):
    """Tungsten's quads, cubes and .wo3 meshes. A primitive's "power" P becomes the radiance
    P / (pi * area) that Tungsten gives it (Quad::powerToRadianceFactor), emitted from its front.
    "smooth" meshes with "recompute_normals" get Tungsten's smooth normals, others flat shading.
    The pinhole camera's "fov" is horizontal: yfov keeps the vertical extent of its resolution."""
    scene = json.load(open(os.path.join(folder, 'scene.json')))
    gltf = Gltf(source)
    bsdfs = {b['name']: b for b in scene['bsdfs']}
    indices = {}
    for prim in scene['primitives']:
        m = tungsten_transform(prim.get('transform', {}))
        kind = prim['type']
        if kind == 'quad':
            mesh = tungsten_quad()
        elif kind == 'cube':
            mesh = tungsten_cube()
        elif kind == 'mesh':
            mesh = read_wo3(os.path.join(folder, prim['file']))
            if prim.get('smooth', False):
                if not prim.get('recompute_normals', False):
                    fail(f"{prim['name']}: a smooth mesh keeps its file's normals, which this does not read")
                mesh = tungsten_smooth_normals(mesh)
        else:
            fail(f"primitive {prim['name']!r} of type {kind!r} is not read")
        mesh = mesh.transformed(m)
        mesh.name = prim['name']
        emission = None
        if 'power' in prim:
            area = sum(math.sqrt(dot(n, n)) / 2 for n in map(mesh.face_normal, mesh.triangles))
            emission = [p / (math.pi * area) for p in rgb(prim['power'])]
        if 'emission' in prim:
            emission = rgb(prim['emission'])
        if emission:
            index = tungsten_material(gltf, bsdfs[prim['bsdf']], f"{prim['bsdf']} ({prim['name']}, emitter)", emission)
        else:
            index = indices.setdefault(prim['bsdf'], None)
            if index is None:
                index = indices[prim['bsdf']] = tungsten_material(gltf, bsdfs[prim['bsdf']], prim['bsdf'])
        gltf.mesh(mesh, index)
    camera = scene['camera']
    if camera['type'] != 'pinhole':
        fail(f"camera of type {camera['type']!r} is not read")
    t = camera['transform']
    width, height = camera['resolution']
    yfov = math.degrees(2 * math.atan(math.tan(math.radians(camera['fov']) / 2) * height / width))
    gltf.camera(look_at(t['position'], t['look_at'], t.get('up', [0, 1, 0])), yfov)
    gltf.write(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--efficiency-aware-mis', required=True, help='a checkout of pgrit/EfficiencyAwareMIS')
    parser.add_argument('--mis-for-correlated-bidir', required=True, help='a checkout of pgrit/MisForCorrelatedBidir')
    parser.add_argument('--tungsten', required=True, help='a checkout of tunabrain/tungsten')
    parser.add_argument('--out', default='scenes', help='folder for the .gltf files (default: scenes)')
    args = parser.parse_args()
    for folder in (args.efficiency_aware_mis, args.mis_for_correlated_bidir, args.tungsten, args.out):
        if not os.path.isdir(folder):
            fail(f"{folder[:80]}: not a folder")
    out = lambda name: os.path.join(args.out, name)
    eam, mis = 'pgrit/EfficiencyAwareMIS@4e0fdc85d143', 'pgrit/MisForCorrelatedBidir@6ba56596b396'
    convert_seesharp_ply(os.path.join(args.efficiency_aware_mis, 'Scenes', 'VeachBidir'),
                         eam + ' Scenes/VeachBidir', out('veach-bidir.gltf'))
    convert_seesharp_obj(os.path.join(args.mis_for_correlated_bidir, 'Scenes', 'LampCaustic', 'LampCaustic.json'),
                         mis + ' Scenes/LampCaustic', out('lamp-caustic.gltf'))
    convert_seesharp_obj(os.path.join(args.mis_for_correlated_bidir, 'Scenes', 'Box', 'LightTop.json'),
                         mis + ' Scenes/Box/LightTop', out('box-light-top.gltf'))
    convert_tungsten(os.path.join(args.tungsten, 'data', 'example-scenes', 'water-caustic'),
                     'tunabrain/tungsten@88ea02044dba data/example-scenes/water-caustic', out('water-caustic.gltf'))


if __name__ == '__main__':
    main()
