#!/usr/bin/env python3
"""Write a Mitsuba XML scene (the benchmark scenes') in pbrt-v4's scene format, for side-by-side
timing against pbrt-v4 (docs/performance.md; /work/shared/measurements/peers.md).

    python3 bench/to_pbrt_v4.py bench/scenes/lamp-in-glass/scene.xml OUT.pbrt -D res=64 \
        [--filter box] [--integrator 'Integrator "mlt" "integer maxdepth" 5'] [--sampler '...']

Only what the benchmark scenes use is converted, and anything else stops the conversion:
  - the perspective sensor (fov and fov_axis, to_world as matrix/lookat/rotate/scale/translate),
    written as `Scale -1 1 1` + `LookAt` (Mitsuba's image x runs along the camera's -x, pbrt's
    along +x) and pbrt's fov of the shorter image axis;
  - the hdrfilm's size (after `<default>`s and -D overrides) and its rfilter: box (radius 0.5,
    pbrt's default), tent (pbrt's "triangle" of radius 1), gaussian (pbrt's, stddev 0.5, radius 2);
  - rectangle and cube shapes (written as world-space triangle meshes with per-vertex normals,
    so that a one-sided area light faces the way Mitsuba's does), OBJ meshes (v, vn, f; faces
    fanned to triangles; no texture coordinates) and spheres (center/radius or a to_world of
    translation and uniform scale; flip_normals becomes ReverseOrientation);
  - diffuse ("rgb reflectance"), twosided (pbrt's diffuse is two-sided anyway: a one-sided
    Mitsuba diffuse differs only on back faces) and dielectric (eta = int_ior / ext_ior; Mitsuba's
    default ext_ior is air, 1.000277) bsdfs; a shape without a bsdf gets Mitsuba's default,
    diffuse 0.5;
  - area emitters as pbrt's "diffuse" area light with "rgb L" = the radiance. pbrt-v4 turns an
    RGB illuminant into the RGB's spectrum times the colour space's illuminant (D65 for sRGB)
    and divides the light's scale by that illuminant's luminance, so an "rgb L" renders as that
    RGB on pbrt's default RGB film: no extra scale is needed.
pbrt-v4 is spectral: RGB reflectances and radiances are uplifted to spectra, so colours near
saturation come out a little different; compare against a reference rendered by pbrt itself.
"""
import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

FILTERS = {"box": 'PixelFilter "box"',
           "tent": 'PixelFilter "triangle" "float xradius" 1 "float yradius" 1',
           "gaussian": 'PixelFilter "gaussian" "float sigma" 0.5 "float xradius" 2 "float yradius" 2'}


def fail(msg):
    sys.exit(f"to_pbrt_v4: {msg}")


# 4x4 matrices as lists of rows
def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def identity():
    return [[float(i == j) for j in range(4)] for i in range(4)]


def xform_point(m, p):
    v = [sum(m[i][k] * p[k] for k in range(3)) + m[i][3] for i in range(4)]
    return [v[0] / v[3], v[1] / v[3], v[2] / v[3]]


def xform_normal(m, n):
    """n by the inverse transpose of m's 3x3 part (cofactor matrix: same direction), normalized."""
    a = [row[:3] for row in m[:3]]
    cof = [[a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3]
            - a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3] for j in range(3)] for i in range(3)]
    det = sum(a[0][j] * cof[0][j] for j in range(3))
    v = [sum(cof[i][k] * n[k] for k in range(3)) * (1 if det > 0 else -1) for i in range(3)]
    return normalize(v)


def normalize(v):
    length = math.sqrt(sum(x * x for x in v))
    return [x / length for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def rotation(axis, degrees):
    x, y, z = normalize(axis)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    t = 1 - c
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0], [0, 0, 0, 1]]


def vec(text):
    return [float(v) for v in text.replace(",", " ").split()]


class Converter:
    def __init__(self, defines):
        self.defines = dict(defines)
        self.bsdfs = {}

    def value(self, el, attr="value"):
        text = el.get(attr)
        if text is None:
            return None
        return re.sub(r"\$(\w+)", lambda m: self.defines[m.group(1)] if m.group(1) in self.defines
                      else fail(f"no value for ${m.group(1)}"), text)

    def params(self, el):
        """The element's direct scalar parameters by name."""
        out = {}
        for child in el:
            if child.tag in ("float", "integer"):
                out[child.get("name")] = float(self.value(child))
            elif child.tag in ("string", "boolean"):
                out[child.get("name")] = self.value(child)
            elif child.tag in ("rgb", "point", "vector"):
                if child.get("value") is not None:
                    out[child.get("name")] = vec(self.value(child))
                else:
                    out[child.get("name")] = [float(self.value(child, a)) for a in "xyz"]
        return out

    def transform(self, el):
        m = identity()
        if el is None:
            return m
        for op in el:
            if op.tag == "matrix":
                v = vec(self.value(op))
                t = [v[0:4], v[4:8], v[8:12], v[12:16]]
            elif op.tag == "translate":
                t = identity()
                for i, a in enumerate("xyz"):
                    t[i][3] = float(self.value(op, a) or 0)
            elif op.tag == "scale":
                t = identity()
                if op.get("value") is not None:
                    s = vec(self.value(op))
                    s = s * 3 if len(s) == 1 else s
                else:
                    s = [float(self.value(op, a) or 1) for a in "xyz"]
                for i in range(3):
                    t[i][i] = s[i]
            elif op.tag == "rotate":
                axis = vec(self.value(op)) if op.get("value") is not None else \
                    [float(self.value(op, a) or 0) for a in "xyz"]
                t = rotation(axis, float(self.value(op, "angle")))
            elif op.tag == "lookat":
                o, target = vec(self.value(op, "origin")), vec(self.value(op, "target"))
                up = vec(self.value(op, "up")) if op.get("up") else [0, 1, 0]
                d = normalize([target[i] - o[i] for i in range(3)])
                left = normalize(cross(up, d))
                new_up = cross(d, left)
                t = [[left[i], new_up[i], d[i], o[i]] for i in range(3)] + [[0, 0, 0, 1]]
            else:
                fail(f"transform <{op.tag}> is not converted")
            m = matmul(t, m)
        return m

    def material(self, el):
        """pbrt Material line for a Mitsuba bsdf element."""
        kind = el.get("type")
        if kind == "twosided":
            inner = el.find("bsdf")
            return self.material(inner)
        p = self.params(el)
        if kind == "diffuse":
            if any(c.tag == "texture" for c in el):
                fail("textured reflectance is not converted")
            r = p.get("reflectance", [0.5])
            r = r * 3 if len(r) == 1 else r
            return 'Material "diffuse" "rgb reflectance" [ %s ]' % " ".join("%g" % v for v in r)
        if kind == "dielectric":
            for name in ("int_ior", "ext_ior", "intIOR", "extIOR"):
                if isinstance(p.get(name), str):
                    fail(f"named IOR {p[name]!r} is not converted")
            eta = p.get("int_ior", p.get("intIOR", 1.5046)) / p.get("ext_ior", p.get("extIOR", 1.000277))
            return 'Material "dielectric" "float eta" %.6g' % eta
        fail(f"bsdf type {kind!r} is not converted")

    def shape_bsdf(self, el):
        ref = el.find("ref")
        if ref is not None:
            return self.bsdfs[ref.get("id")]
        b = el.find("bsdf")
        if b is not None:
            return self.material(b)
        return 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'

    def mesh(self, kind, el, m, scene_dir):
        if kind == "rectangle":
            verts = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]
            normals = [[0, 0, 1]] * 4
            tris = [[0, 1, 2], [2, 3, 0]]
        elif kind == "cube":
            verts, normals, tris = [], [], []
            for axis in range(3):
                for sign in (-1, 1):
                    n = [0, 0, 0]
                    n[axis] = sign
                    u, v = [0, 0, 0], [0, 0, 0]
                    u[(axis + 1) % 3], v[(axis + 2) % 3] = 1, 1
                    if sign < 0:
                        u, v = v, u  # keep (u, v, n) right-handed so the winding faces out
                    base = len(verts)
                    for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                        verts.append([n[i] + a * u[i] + b * v[i] for i in range(3)])
                        normals.append(n)
                    tris += [[base, base + 1, base + 2], [base + 2, base + 3, base]]
        elif kind == "obj":
            verts, normals, tris = self.read_obj(os.path.join(scene_dir, self.params(el)["filename"]))
        else:
            fail(f"shape type {kind!r} is not converted")
        if self.params(el).get("flip_normals") == "true":
            normals = [[-c for c in n] for n in normals]
            tris = [[t[0], t[2], t[1]] for t in tris]
        P = [xform_point(m, p) for p in verts]
        N = [xform_normal(m, n) for n in normals] if normals else None
        out = 'Shape "trianglemesh"\n    "integer indices" [ %s ]\n    "point3 P" [ %s ]' % (
            " ".join(str(i) for t in tris for i in t), " ".join("%.9g" % c for p in P for c in p))
        if N:
            out += '\n    "normal N" [ %s ]' % " ".join("%.7g" % c for n in N for c in n)
        return out

    @staticmethod
    def read_obj(path):
        vs, vns, verts, normals, tris, index = [], [], [], [], [], {}
        with open(path) as f:
            for line in f:
                w = line.split()
                if not w:
                    continue
                if w[0] == "v":
                    vs.append([float(x) for x in w[1:4]])
                elif w[0] == "vn":
                    vns.append([float(x) for x in w[1:4]])
                elif w[0] == "f":
                    face = []
                    for corner in w[1:]:
                        parts = corner.split("/")
                        vi = int(parts[0])
                        ni = int(parts[2]) if len(parts) > 2 and parts[2] else 0
                        key = (vi, ni)
                        if key not in index:
                            index[key] = len(verts)
                            verts.append(vs[vi - 1 if vi > 0 else vi])
                            normals.append(vns[ni - 1 if ni > 0 else ni] if ni else None)
                        face.append(index[key])
                    tris += [[face[0], face[i], face[i + 1]] for i in range(1, len(face) - 1)]
        if any(n is None for n in normals):
            normals = None
        return verts, normals, tris

    def shape(self, el, scene_dir):
        kind = el.get("type")
        lines = ["AttributeBegin", "  " + self.shape_bsdf(el)]
        emitter = el.find("emitter")
        if emitter is not None:
            if emitter.get("type") != "area":
                fail(f"emitter type {emitter.get('type')!r} on a shape is not converted")
            L = self.params(emitter).get("radiance")
            if L is None or any(c.tag != "rgb" for c in emitter):
                fail("area emitter radiance must be an rgb")
            L = L * 3 if len(L) == 1 else L
            lines.append('  AreaLightSource "diffuse" "rgb L" [ %s ]' % " ".join("%g" % v for v in L))
        m = self.transform(el.find("transform"))
        if kind == "sphere":
            p = self.params(el)
            center, radius = p.get("center", [0, 0, 0]), p.get("radius", 1.0)
            # to_world may only translate and scale uniformly
            s = [math.sqrt(sum(m[i][j] ** 2 for i in range(3))) for j in range(3)]
            if max(s) - min(s) > 1e-6 * max(s):
                fail("a sphere's to_world must scale uniformly")
            center, radius = xform_point(m, center), radius * s[0]
            lines.append("  Translate %.9g %.9g %.9g" % tuple(center))
            if p.get("flip_normals") == "true":
                lines.append("  ReverseOrientation")
            lines.append('  Shape "sphere" "float radius" %.9g' % radius)
        else:
            lines.append("  " + self.mesh(kind, el, m, scene_dir).replace("\n", "\n  "))
        lines.append("AttributeEnd")
        return "\n".join(lines)

    def camera(self, sensor, filter_override):
        if sensor.get("type") != "perspective":
            fail(f"sensor type {sensor.get('type')!r} is not converted")
        p = self.params(sensor)
        film = sensor.find("film")
        fp = self.params(film)
        w, h = int(fp.get("width", 768)), int(fp.get("height", 576))
        fov = p["fov"]
        axis = p.get("fov_axis", "x")
        t = math.tan(math.radians(fov) / 2)
        # pbrt's fov spans the shorter image axis
        if axis == "x" and w > h:
            t *= h / w
        elif axis == "y" and h > w:
            t *= w / h
        elif axis not in ("x", "y", "smaller"):
            fail(f"fov_axis {axis!r} is not converted")
        fov_pbrt = math.degrees(2 * math.atan(t))
        m = self.transform(sensor.find("transform"))
        o = [m[i][3] for i in range(3)]
        d = [m[i][2] for i in range(3)]
        up = [m[i][1] for i in range(3)]
        rfilter = film.find("rfilter")
        kind = filter_override or (rfilter.get("type") if rfilter is not None else "gaussian")
        if kind not in FILTERS:
            fail(f"rfilter {kind!r} is not converted")
        return "\n".join([
            "Scale -1 1 1",
            "LookAt %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g" % tuple(o + [o[i] + d[i] for i in range(3)] + up),
            'Camera "perspective" "float fov" %.9g' % fov_pbrt,
            'Film "rgb" "integer xresolution" %d "integer yresolution" %d "string filename" "pbrt.exr"' % (w, h),
            FILTERS[kind]])

    def convert(self, path, integrator, sampler, filter_override):
        root = ET.parse(path).getroot()
        for d in root.iter("default"):
            self.defines.setdefault(d.get("name"), d.get("value"))
        scene_dir = os.path.dirname(os.path.abspath(path))
        head, body = [], []
        sensor = root.find("sensor")
        if sensor is None:
            fail("no sensor")
        head.append(self.camera(sensor, filter_override))
        head.append(sampler)
        head.append(integrator)
        for el in root:
            if el.tag == "bsdf":
                self.bsdfs[el.get("id")] = self.material(el)
            elif el.tag == "shape":
                body.append(self.shape(el, scene_dir))
            elif el.tag == "emitter":
                fail(f"emitter type {el.get('type')!r} outside a shape is not converted")
            elif el.tag not in ("default", "integrator", "sensor"):
                fail(f"<{el.tag}> is not converted")
        return "# converted from %s by bench/to_pbrt_v4.py\n%s\n\nWorldBegin\n\n%s\n" % (
            path, "\n".join(head), "\n\n".join(body))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("out")
    parser.add_argument("-D", "--define", action="append", default=[], help="override a scene <default>: name=value")
    parser.add_argument("--filter", choices=sorted(FILTERS), help="pixel filter (default: the scene's rfilter)")
    parser.add_argument("--integrator", default='Integrator "mlt" "integer maxdepth" 5',
                        help="pbrt Integrator line (default: mlt, maxdepth 5; pbrt's --spp sets its mutations per pixel)")
    parser.add_argument("--sampler", default='Sampler "zsobol" "integer pixelsamples" 16',
                        help="pbrt Sampler line (mlt uses its own)")
    args = parser.parse_args()
    defines = {}
    for d in args.define:
        name, _, value = d.partition("=")
        defines[name] = value
    try:
        text = Converter(defines).convert(args.scene, args.integrator, args.sampler, args.filter)
    except OSError as e:
        sys.exit(f"{e.filename}: {e.strerror}")
    with open(args.out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
