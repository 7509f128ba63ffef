#!/usr/bin/env python3
"""Writes the scenes ddish ships (scenes/*.gltf + .bin + .ddish.json sidecars).

Metres, +Y up, glTF right-handed; front faces wind counter-clockwise. Room walls face inwards
(single-sided); blocks and wall slabs are closed solids facing outwards, so a probe inside any
geometry sees only back faces. The Cornell boxes are open at the front like the original, with the
camera outside looking in; the two rooms are closed with the camera inside. The environment
radiance is 0 everywhere, so light that leaves through the opening is lost, as in the original.

Run from anywhere: python3 scripts/make_scenes.py [OUTPUT_DIR]  (default: scenes/ of the repo).
"""
import json
import math
import os
import struct
import sys
import zlib

WHITE = [0.725, 0.71, 0.68, 1.0]
RED = [0.63, 0.065, 0.05, 1.0]
GREEN = [0.14, 0.45, 0.091, 1.0]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    length = math.sqrt(sum(x * x for x in a))
    return [x / length for x in a]


class Part:
    """Flat-shaded quads of one material: one glTF primitive."""

    def __init__(self, material):
        self.material = material
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []

    def quad(self, origin, u, v, facing):
        """Rectangle origin, origin+u, origin+u+v, origin+v whose front faces `facing`."""
        n = norm(cross(u, v))
        if sum(n[i] * facing[i] for i in range(3)) < 0.99:
            raise ValueError("quad winding does not face %r" % (facing,))
        base = len(self.positions)
        lu = math.sqrt(sum(x * x for x in u))
        lv = math.sqrt(sum(x * x for x in v))
        corners = [origin, add(origin, u), add(add(origin, u), v), add(origin, v)]
        for p, uv in zip(corners, [(0, lv), (lu, lv), (lu, 0), (0, 0)]):
            self.positions.append(p)
            self.normals.append(n)
            self.uvs.append(list(uv))
        self.indices += [base, base + 1, base + 2, base, base + 2, base + 3]

    # Axis-aligned rectangles: `axis` is the constant coordinate, `sign` the facing direction.
    def rect(self, axis, value, sign, lo, hi):
        """lo/hi: the rectangle's two other coordinates, in axis order (x,y,z minus axis)."""
        a, b = [i for i in range(3) if i != axis]
        origin = [0.0, 0.0, 0.0]
        origin[axis], origin[a], origin[b] = value, lo[0], lo[1]
        u = [0.0, 0.0, 0.0]
        v = [0.0, 0.0, 0.0]
        u[a] = hi[0] - lo[0]
        v[b] = hi[1] - lo[1]
        facing = [0.0, 0.0, 0.0]
        facing[axis] = float(sign)
        if sum(norm(cross(u, v))[i] * facing[i] for i in range(3)) < 0:
            origin[a], origin[b] = lo[0], lo[1]
            u, v = v, u
        self.quad(origin, u, v, facing)

    def box(self, lo, hi, outward=True):
        """Six faces of an axis-aligned box, facing out (a solid) or in (a room)."""
        for axis in range(3):
            a, b = [i for i in range(3) if i != axis]
            for value, sign in ((lo[axis], -1), (hi[axis], 1)):
                self.rect(axis, value, sign if outward else -sign, (lo[a], lo[b]), (hi[a], hi[b]))


class Gltf:
    def __init__(self, name):
        self.name = name
        self.doc = {"asset": {"version": "2.0", "generator": "ddish scripts/make_scenes.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": []}
        self.bin = bytearray()
        self.extensions = set()

    def material(self, name, color, metallic=0.0, roughness=1.0, emissive=None, strength=None):
        m = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": color, "metallicFactor": metallic, "roughnessFactor": roughness}}
        if emissive:
            m["emissiveFactor"] = emissive
        if strength:
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
            self.extensions.add("KHR_materials_emissive_strength")
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin),
                                        "byteLength": len(data), "target": target})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, values, kind, minmax=False):
        width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[kind]
        flat = [x for v in values for x in (v if width > 1 else [v])]
        acc = {"bufferView": self._view(struct.pack("<%df" % len(flat), *flat), 34962),
               "componentType": 5126, "count": len(values), "type": kind}
        if minmax:
            acc["min"] = [min(v[i] for v in values) for i in range(width)]
            acc["max"] = [max(v[i] for v in values) for i in range(width)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def _times(self, values):
        data = struct.pack("<%df" % len(values), *values)
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        self.doc["accessors"].append({"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": 5126,
                                      "count": len(values), "type": "SCALAR",
                                      "min": [min(values)], "max": [max(values)]})
        return len(self.doc["accessors"]) - 1

    def mesh(self, name, parts):
        prims = []
        for p in parts:
            idx = self._view(struct.pack("<%dH" % len(p.indices), *p.indices), 34963)
            self.doc["accessors"].append({"bufferView": idx, "componentType": 5123,
                                          "count": len(p.indices), "type": "SCALAR"})
            indices = len(self.doc["accessors"]) - 1
            prims.append({"attributes": {"POSITION": self._accessor(p.positions, "VEC3", True),
                                         "NORMAL": self._accessor(p.normals, "VEC3"),
                                         "TEXCOORD_0": self._accessor(p.uvs, "VEC2")},
                          "indices": indices, "material": p.material})
        self.doc["meshes"].append({"name": name, "primitives": prims})
        return len(self.doc["meshes"]) - 1

    def node(self, node, root=True):
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def camera(self, name, eye, target, yfov):
        """A camera node at eye looking at target (up +Y): its -Z axis points at the target."""
        self.doc.setdefault("cameras", []).append(
            {"name": name, "type": "perspective",
             "perspective": {"yfov": yfov, "znear": 0.01, "zfar": 100.0}})
        f = norm(sub(target, eye))
        yaw = math.atan2(-f[0], -f[2])
        pitch = math.asin(max(-1.0, min(1.0, f[1])))
        # rotation = yaw about Y, then pitch about X: q = q_yaw * q_pitch (xyzw)
        cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
        cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
        q = [cy * sp, sy * cp, -sy * sp, cy * cp]
        return self.node({"name": name, "camera": len(self.doc["cameras"]) - 1,
                          "translation": eye, "rotation": q})

    def light(self, light):
        self.extensions.add("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})
        lights["lights"].append(light)
        return len(lights["lights"]) - 1

    def animate_translation(self, name, node, times, values, interpolation="LINEAR"):
        t = self._times(times)
        v = self._accessor(values, "VEC3")
        self.doc.setdefault("animations", []).append({
            "name": name,
            "samplers": [{"input": t, "output": v, "interpolation": interpolation}],
            "channels": [{"sampler": 0, "target": {"node": node, "path": "translation"}}]})

    def write(self, out_dir, sidecar):
        """sidecar: the NAME.ddish.json object, or None for a plain glTF file with no sidecar
        (what a user's model looks like: ddish's defaults and glTF's units apply)."""
        if self.extensions:
            self.doc["extensionsUsed"] = sorted(self.extensions)
        self.doc["buffers"] = [{"uri": self.name + ".bin", "byteLength": len(self.bin)}]
        with open(os.path.join(out_dir, self.name + ".bin"), "wb") as f:
            f.write(bytes(self.bin))
        with open(os.path.join(out_dir, self.name + ".gltf"), "w") as f:
            json.dump(self.doc, f, indent=1)
            f.write("\n")
        sidecar_path = os.path.join(out_dir, self.name + ".ddish.json")
        if sidecar is None:
            if os.path.exists(sidecar_path):
                os.remove(sidecar_path)
            return
        with open(sidecar_path, "w") as f:
            json.dump(sidecar, f, indent=2)
            f.write("\n")


def y_rotation(degrees):
    h = math.radians(degrees) / 2
    return [0.0, math.sin(h), 0.0, math.cos(h)]


# The Cornell box: x, z in [-1, 1], y in [0, 2]; red wall at x = -1, green at x = +1.
def cornell_room(g, light_hole):
    white = g.material("White", WHITE)
    red = g.material("Red", RED)
    green = g.material("Green", GREEN)
    walls, left, right = Part(white), Part(red), Part(green)
    walls.rect(1, 0.0, 1, (-1, -1), (1, 1))      # floor
    walls.rect(2, -1.0, 1, (-1, 0), (1, 2))      # back wall; the front (+z) is open
    left.rect(0, -1.0, 1, (0, -1), (2, 1))
    right.rect(0, 1.0, -1, (0, -1), (2, 1))
    parts = [walls, left, right]
    if light_hole:
        h = 0.25  # the light fills a 0.5 m square hole in the ceiling
        walls.rect(1, 2.0, -1, (-1, -1), (1, -h))
        walls.rect(1, 2.0, -1, (-1, h), (1, 1))
        walls.rect(1, 2.0, -1, (-1, -h), (-h, h))
        walls.rect(1, 2.0, -1, (h, -h), (1, h))
        lamp = Part(g.material("Light", [0.78, 0.78, 0.78, 1.0], emissive=[1.0, 0.85, 0.65], strength=15.0))
        lamp.rect(1, 2.0, -1, (-h, -h), (h, h))
        parts.append(lamp)
    else:
        walls.rect(1, 2.0, -1, (-1, -1), (1, 1))
    g.node({"name": "Room", "mesh": g.mesh("Room", parts)})
    return white


# Solids stand 1 mm above the floor: a bottom face coplanar with the floor would tie with it,
# and a ray from inside the solid could then report the floor's front face.
LIFT = 0.001


def block(g, name, material, size, position, degrees):
    part = Part(material)
    sx, sy, sz = size
    part.box([-sx / 2, LIFT, -sz / 2], [sx / 2, sy, sz / 2], outward=True)
    return g.node({"name": name, "mesh": g.mesh(name, [part]), "translation": position,
                   "rotation": y_rotation(degrees)})


# The classic view: 2.88 m in front of the opening (800 of 555 units), 39.3 degree field.
CORNELL_CAMERA = ([0.0, 1.0, 3.88], [0.0, 1.0, 0.0], math.radians(39.3))


def cornell_box(out_dir):
    g = Gltf("cornell_box")
    white = cornell_room(g, light_hole=True)
    block(g, "ShortBlock", white, (0.6, 0.6, 0.6), [0.33, 0.0, 0.28], -17.0)
    block(g, "TallBlock", white, (0.6, 1.2, 0.6), [-0.33, 0.0, -0.3], 17.0)
    g.camera("Camera", *CORNELL_CAMERA)
    g.write(out_dir, {"light_units": "radiometric", "environment": {"radiance": [0, 0, 0]}, "probe_grid": {"counts": [8, 8, 8]},
                      "camera": "Camera"})


def cornell_spot(out_dir):
    g = Gltf("cornell_spot")
    white = cornell_room(g, light_hole=False)
    metal = g.material("GlossyMetal", [0.95, 0.64, 0.54, 1.0], metallic=1.0, roughness=0.2)
    block(g, "ShortBlock", white, (0.6, 0.6, 0.6), [0.33, 0.0, 0.28], -17.0)
    block(g, "TallBlock", metal, (0.6, 1.2, 0.6), [-0.33, 0.0, -0.3], 17.0)
    # Radiant intensity 25 W/sr gives ~7 W/m^2 on the floor 1.9 m below.
    spot = g.light({"name": "Spot", "type": "spot", "color": [1.0, 0.9, 0.75], "intensity": 25.0,
                    "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.8}})
    s = math.sqrt(0.5)
    g.node({"name": "Spot", "translation": [0.0, 1.9, 0.0], "rotation": [-s, 0.0, 0.0, s],
            "extensions": {"KHR_lights_punctual": {"light": spot}}})  # -Z turned to -Y
    g.camera("Camera", *CORNELL_CAMERA)
    g.write(out_dir, {"light_units": "radiometric", "environment": {"radiance": [0, 0, 0]}, "probe_grid": {"counts": [8, 8, 8]},
                      "camera": "Camera"})


def cornell_animated(out_dir):
    g = Gltf("cornell_animated")
    white = cornell_room(g, light_hole=True)
    short = block(g, "ShortBlock", white, (0.6, 0.6, 0.6), [0.33, 0.0, 0.28], -17.0)
    block(g, "TallBlock", white, (0.6, 1.2, 0.6), [-0.33, 0.0, -0.3], 17.0)
    # The short block slides towards the red wall and back over 4 s.
    g.animate_translation("SlideShortBlock", short, [0.0, 2.0, 4.0],
                          [[0.33, 0.0, 0.28], [-0.35, 0.0, 0.45], [0.33, 0.0, 0.28]])
    g.camera("Camera", *CORNELL_CAMERA)
    g.write(out_dir, {"light_units": "radiometric", "environment": {"radiance": [0, 0, 0]}, "probe_grid": {"counts": [8, 8, 8]},
                      "camera": "Camera"})


# cornell_light: where the point light is (STEP keys, so it jumps), in seconds. At whole-number
# frame rates every event falls on a whole frame (at 30 fps 4 s = frame 120, ...); the 4 s run-in
# holds the 1 / (1 - hysteresis) updates of the probes' warm-up (100 at 0.99: 25 fps or more), so
# results section 3 measures each event from a running average at full hysteresis.
LIGHT_A = [-0.5, 1.6, 0.4]       # near the red wall, front
LIGHT_B = [0.5, 1.6, -0.5]       # near the green wall, back
LIGHT_HOUSING = [0.0, 1.0, -1.5]  # inside a closed box behind the back wall: switched off
LIGHT_TIMELINE = [(0.0, LIGHT_A), (4.0, LIGHT_B), (14.0, LIGHT_HOUSING), (24.0, LIGHT_B)]


def cornell_light(out_dir):
    """cornell_box (its emissive ceiling quad stays on as a fill light) plus a point light that
    jumps from A to B at 4 s, is switched off at 14 s and on again at B at 24 s. Core glTF cannot
    animate a light's intensity, so "off" is a move into a closed housing outside the room: every
    ray from the light meets the housing, in the path tracer and in the cube shadow map alike."""
    g = Gltf("cornell_light")
    white = cornell_room(g, light_hole=True)
    block(g, "ShortBlock", white, (0.6, 0.6, 0.6), [0.33, 0.0, 0.28], -17.0)
    block(g, "TallBlock", white, (0.6, 1.2, 0.6), [-0.33, 0.0, -0.3], 17.0)
    housing = Part(g.material("Housing", [0.2, 0.2, 0.2, 1.0]))
    c, r = LIGHT_HOUSING, 0.2
    housing.box([c[0] - r, c[1] - r, c[2] - r], [c[0] + r, c[1] + r, c[2] + r], outward=True)
    g.node({"name": "LampHousing", "mesh": g.mesh("LampHousing", [housing])})
    lamp = g.light({"name": "Lamp", "type": "point", "color": [1.0, 0.9, 0.75], "intensity": 6.0})
    node = g.node({"name": "Lamp", "translation": LIGHT_A,
                   "extensions": {"KHR_lights_punctual": {"light": lamp}}})
    g.animate_translation("MoveAndSwitchLamp", node, [t for t, _ in LIGHT_TIMELINE],
                          [p for _, p in LIGHT_TIMELINE], interpolation="STEP")
    g.camera("Camera", *CORNELL_CAMERA)
    # The probe grid covers the room only (the housing outside it would stretch an automatic grid):
    # the same 8 x 8 x 8 probes as cornell_box.
    g.write(out_dir, {"light_units": "radiometric", "environment": {"radiance": [0, 0, 0]},
                      "probe_grid": {"counts": [8, 8, 8], "bounds": {"min": [-1, 0, -1], "max": [1, 2, 1]}},
                      "camera": "Camera"})


def two_rooms(out_dir):
    """Room A (x in [-3, 0], lit by a point light) and room B (x in [0.2, 3.2], unlit) on either
    side of a 0.2 m wall with a 1 m x 2 m door; 2.5 m high, z in [-1.5, 1.5]."""
    g = Gltf("two_rooms")
    white = g.material("White", WHITE)
    warm = g.material("WarmWall", [0.8, 0.55, 0.35, 1.0])
    blue = g.material("BlueWall", [0.3, 0.4, 0.75, 1.0])
    rooms, wall_a, wall_b, slab = Part(white), Part(warm), Part(blue), Part(white)
    H, Z, T = 2.5, 1.5, 0.2            # height, half depth, wall thickness
    DZ, DH = 0.5, 2.0                  # door half width, door height
    for (x0, x1), side in (((-3.0, 0.0), wall_a), ((T, 3.2), wall_b)):
        rooms.rect(1, 0.0, 1, (x0, -Z), (x1, Z))   # floor
        rooms.rect(1, H, -1, (x0, -Z), (x1, Z))    # ceiling
        rooms.rect(2, -Z, 1, (x0, 0), (x1, H))     # back
        rooms.rect(2, Z, -1, (x0, 0), (x1, H))     # front
    wall_a.rect(0, -3.0, 1, (0, -Z), (H, Z))       # room A's far wall, warm
    wall_b.rect(0, 3.2, -1, (0, -Z), (H, Z))       # room B's far wall, blue
    rooms.rect(1, 0.0, 1, (0, -DZ), (T, DZ))       # the door's threshold
    # The dividing wall: a closed solid with a door, all faces outwards.
    for x, sign in ((0.0, -1), (T, 1)):
        slab.rect(0, x, sign, (0, -Z), (H, -DZ))
        slab.rect(0, x, sign, (0, DZ), (H, Z))
        slab.rect(0, x, sign, (DH, -DZ), (H, DZ))
    slab.rect(2, -DZ, 1, (0, 0), (T, DH))          # door jambs
    slab.rect(2, DZ, -1, (0, 0), (T, DH))
    slab.rect(1, DH, -1, (0, -DZ), (T, DZ))        # door head
    slab.rect(1, H, 1, (0, -Z), (T, Z))            # top and ends of the slab
    slab.rect(2, -Z, -1, (0, 0), (T, H))
    slab.rect(2, Z, 1, (0, 0), (T, H))
    slab.rect(1, 0.0, -1, (0, -Z), (T, -DZ))       # bottom beside the door
    slab.rect(1, 0.0, -1, (0, DZ), (T, Z))
    g.node({"name": "Rooms", "mesh": g.mesh("Rooms", [rooms, wall_a, wall_b, slab])})
    box = Part(white)
    box.box([-0.4, LIFT, -0.4], [0.4, 0.8, 0.4], outward=True)
    g.node({"name": "Crate", "mesh": g.mesh("Crate", [box]), "translation": [-1.6, 0.0, -0.6],
            "rotation": y_rotation(25.0)})
    lamp = g.light({"name": "Lamp", "type": "point", "color": [1.0, 0.92, 0.8], "intensity": 30.0})
    g.node({"name": "Lamp", "translation": [-1.8, 2.1, 0.6],
            "extensions": {"KHR_lights_punctual": {"light": lamp}}})
    g.camera("Camera", [3.0, 1.5, 1.3], [0.0, 1.0, 0.0], math.radians(60.0))
    g.write(out_dir, {"light_units": "radiometric", "environment": {"radiance": [0, 0, 0]}, "probe_grid": {"counts": [12, 4, 6]},
                      "camera": "Camera"})


def thin_wall(out_dir):
    """Issue 19's leak test: room A (x in [-3, 0]) lit by an emissive ceiling panel and room B
    (x in [0.05, 3.05]) with no light, on either side of a closed 0.05 m wall with no opening, far
    thinner than the 0.5 m probe cells; 2.5 m high, z in [-1.5, 1.5]. No light can reach room B,
    so everything the rasterizer shows there is light leaked through the wall by the probes."""
    g = Gltf("thin_wall")
    white = g.material("White", WHITE)
    rooms, slab = Part(white), Part(white)
    H, Z, T = 2.5, 1.5, 0.05
    for x0, x1 in ((-3.0, 0.0), (T, 3.0 + T)):
        rooms.rect(1, 0.0, 1, (x0, -Z), (x1, Z))   # floor
        rooms.rect(1, H, -1, (x0, -Z), (x1, Z))    # ceiling
        rooms.rect(2, -Z, 1, (x0, 0), (x1, H))     # back
        rooms.rect(2, Z, -1, (x0, 0), (x1, H))     # front
    rooms.rect(0, -3.0, 1, (0, -Z), (H, Z))        # room A's far wall
    rooms.rect(0, 3.0 + T, -1, (0, -Z), (H, Z))    # room B's far wall
    # The dividing wall: a closed slab, all faces outwards.
    slab.rect(0, 0.0, -1, (0, -Z), (H, Z))
    slab.rect(0, T, 1, (0, -Z), (H, Z))
    slab.rect(1, H, 1, (0, -Z), (T, Z))
    slab.rect(1, 0.0, -1, (0, -Z), (T, Z))
    slab.rect(2, -Z, -1, (0, 0), (T, H))
    slab.rect(2, Z, 1, (0, 0), (T, H))
    lamp = Part(g.material("Light", [0.78, 0.78, 0.78, 1.0], emissive=[1.0, 0.85, 0.65], strength=15.0))
    lamp.rect(1, H - 0.001, -1, (-2.0, -0.5), (-1.0, 0.5))
    g.node({"name": "Rooms", "mesh": g.mesh("Rooms", [rooms, slab, lamp])})
    g.camera("Camera", [2.9, 1.3, 1.3], [0.0, 1.0, -0.4], math.radians(60.0))
    g.write(out_dir, {"light_units": "radiometric", "environment": {"radiance": [0, 0, 0]},
                      "probe_grid": {"counts": [12, 5, 6]}, "camera": "Camera"})


def uv_sphere(material, radius, segments=32, rings=16):
    """A sphere around the origin, front faces outwards: `segments` around +Y, `rings` pole to
    pole, smooth normals."""
    part = Part(material)
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for k in range(segments + 1):
            phi = 2.0 * math.pi * k / segments
            n = [math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi)]
            part.positions.append([radius * c for c in n])
            part.normals.append(n)
            part.uvs.append([k / segments, r / rings])
    row = segments + 1
    for r in range(rings):
        for k in range(segments):
            a, b = r * row + k, (r + 1) * row + k
            if r > 0:
                part.indices += [a, b, a + 1]
            if r < rings - 1:
                part.indices += [a + 1, b, b + 1]
    return part


def open_sphere(out_dir):
    """A grey sphere (radius 0.5 m, albedo 0.5) centred 2 m up, alone in open space: no camera, no
    light, no sidecar, like most glTF sample models. ddish frames it (scene/framing.h), lights it
    with the default sky and surrounds it with probes (ProbeGrid::fit_auto_around)."""
    g = Gltf("open_sphere")
    grey = g.material("Grey", [0.5, 0.5, 0.5, 1.0])
    g.node({"name": "Sphere", "mesh": g.mesh("Sphere", [uv_sphere(grey, 0.5)]),
            "translation": [0.3, 2.0, -0.4]})
    g.write(out_dir, None)


# photometric_lamp: a point light of PHOTOMETRIC_CANDELA cd, PHOTOMETRIC_HEIGHT m above a white
# floor, in glTF's own units (no sidecar). At the foot of the lamp the floor receives
# E = I / 683 / h^2 W/m^2 and reflects L = albedo * E / pi (tests/app/lighting_cli_test.cpp).
PHOTOMETRIC_CANDELA = 683.0
PHOTOMETRIC_HEIGHT = 2.0
PHOTOMETRIC_ALBEDO = 0.8


def photometric_lamp(out_dir):
    """A 20 x 20 m white floor (albedo 0.8) and a white point light of 683 cd (1 W/sr) 2 m above
    its centre; the camera 1 m above the floor looks straight down at the lamp's foot (10 degree
    field). Nothing else: the floor cannot light itself, so its radiance is the lamp's alone."""
    g = Gltf("photometric_lamp")
    floor = Part(g.material("Floor", [PHOTOMETRIC_ALBEDO, PHOTOMETRIC_ALBEDO, PHOTOMETRIC_ALBEDO, 1.0]))
    floor.rect(1, 0.0, 1, (-10, -10), (10, 10))
    g.node({"name": "Floor", "mesh": g.mesh("Floor", [floor])})
    lamp = g.light({"name": "Lamp", "type": "point", "color": [1.0, 1.0, 1.0],
                    "intensity": PHOTOMETRIC_CANDELA})
    g.node({"name": "Lamp", "translation": [0.0, PHOTOMETRIC_HEIGHT, 0.0],
            "extensions": {"KHR_lights_punctual": {"light": lamp}}})
    # Looking down -Y: -Z of the camera node turned to -Y (a -90 degree turn about X).
    s = math.sqrt(0.5)
    g.doc.setdefault("cameras", []).append(
        {"name": "Camera", "type": "perspective",
         "perspective": {"yfov": math.radians(10.0), "znear": 0.01, "zfar": 100.0}})
    g.node({"name": "Camera", "camera": len(g.doc["cameras"]) - 1, "translation": [0.0, 1.0, 0.0],
            "rotation": [-s, 0.0, 0.0, s]})
    g.write(out_dir, None)


# instanced_boxes: one 0.4 m cube drawn three times by EXT_mesh_gpu_instancing under a node at
# INSTANCING_NODE: (translation, rotation xyzw, scale) per instance.
INSTANCING_NODE = [0.0, 1.0, 0.0]
INSTANCES = [([-1.0, 0.2, 0.0], [0.0, 0.0, 0.0, 1.0], [1.0, 1.0, 1.0]),
             ([0.0, 0.2, 0.0], y_rotation(45.0), [1.0, 1.0, 1.0]),
             ([1.0, 0.4, 0.0], [0.0, 0.0, 0.0, 1.0], [2.0, 2.0, 2.0])]


def instanced_boxes(out_dir):
    """Three grey cubes from one mesh, placed by EXT_mesh_gpu_instancing: the second turned 45
    degrees about +Y, the third twice the size. World bounds x in [-1.2, 1.4], y in [1, 1.8],
    z in [-0.4, 0.4] (the third cube's half size 0.4). No camera, no light, no sidecar."""
    g = Gltf("instanced_boxes")
    cube = Part(g.material("Grey", [0.5, 0.5, 0.5, 1.0]))
    cube.box([-0.2, -0.2, -0.2], [0.2, 0.2, 0.2], outward=True)
    mesh = g.mesh("Cube", [cube])
    attributes = {"TRANSLATION": g._accessor([t for t, _, _ in INSTANCES], "VEC3"),
                  "ROTATION": g._accessor([r for _, r, _ in INSTANCES], "VEC4"),
                  "SCALE": g._accessor([sc for _, _, sc in INSTANCES], "VEC3")}
    for a in attributes.values():  # instance attributes are not vertex data
        del g.doc["bufferViews"][g.doc["accessors"][a]["bufferView"]]["target"]
    g.extensions.add("EXT_mesh_gpu_instancing")
    g.node({"name": "Cubes", "mesh": mesh, "translation": INSTANCING_NODE,
            "extensions": {"EXT_mesh_gpu_instancing": {"attributes": attributes}}})
    g.write(out_dir, None)


UNLIT_COLOR = [0.2, 0.6, 0.9]


def unlit_panel(out_dir):
    """A 1 x 1 m panel facing +Z at the origin with a KHR_materials_unlit material of base colour
    UNLIT_COLOR, lit head-on by a directional light of 3415 lux (5 W/m^2) that must not change
    it; the camera 2 m in front sees nothing but the panel (20 degree field). No sidecar."""
    g = Gltf("unlit_panel")
    m = g.material("Unlit", UNLIT_COLOR + [1.0])
    g.doc["materials"][m]["extensions"] = {"KHR_materials_unlit": {}}
    g.extensions.add("KHR_materials_unlit")
    panel = Part(m)
    panel.rect(2, 0.0, 1, (-0.5, -0.5), (0.5, 0.5))
    g.node({"name": "Panel", "mesh": g.mesh("Panel", [panel])})
    sun = g.light({"name": "Sun", "type": "directional", "intensity": 5.0 * 683.0})
    g.node({"name": "Sun", "translation": [0.0, 0.0, 3.0],
            "extensions": {"KHR_lights_punctual": {"light": sun}}})  # shines along -Z
    g.camera("Camera", [0.0, 0.0, 2.0], [0.0, 0.0, 0.0], math.radians(20.0))
    g.write(out_dir, None)


def png_rgba(width, height, pixels):
    """A PNG file's bytes for rows of RGBA8 pixels (row 0 at the top), with the standard library."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in pixels)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def clamped_texture(out_dir):
    """A 3 x 1 m unlit panel facing +Z whose u runs from -1 to 2 over a 2 x 2 texture, red in its
    left column and blue in its right, sampled with wrapS CLAMP_TO_EDGE: u < 0 shows the red edge
    texel, u > 1 the blue one (REPEAT would show the texture three times). Unlit, so a pixel's
    radiance is the texel's colour; the camera 2 m in front sees the panel edge to edge in a 3:1
    image (28.07 degree field). No light, no sidecar."""
    g = Gltf("clamped_texture")
    red, blue = (255, 0, 0, 255), (0, 0, 255, 255)
    png = png_rgba(2, 2, [[red, blue], [red, blue]])
    while len(g.bin) % 4:
        g.bin.append(0)
    g.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(g.bin), "byteLength": len(png)})
    g.bin += png
    g.doc["images"] = [{"name": "RedBlue", "mimeType": "image/png",
                        "bufferView": len(g.doc["bufferViews"]) - 1}]
    g.doc["samplers"] = [{"wrapS": 33071, "wrapT": 10497, "magFilter": 9729, "minFilter": 9987}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}]
    m = g.material("ClampedUnlit", [1.0, 1.0, 1.0, 1.0])
    g.doc["materials"][m]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    g.doc["materials"][m]["extensions"] = {"KHR_materials_unlit": {}}
    g.extensions.add("KHR_materials_unlit")
    panel = Part(m)
    panel.rect(2, 0.0, 1, (-1.5, -0.5), (1.5, 0.5))
    panel.uvs = [[-1.0 + (p[0] + 1.5), 0.5 - p[1]] for p in panel.positions]  # u = x + 0.5, v down
    g.node({"name": "Panel", "mesh": g.mesh("Panel", [panel])})
    g.camera("Camera", [0.0, 0.0, 2.0], [0.0, 0.0, 0.0], 2.0 * math.atan(0.25))
    g.write(out_dir, None)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes")
    os.makedirs(out_dir, exist_ok=True)
    import feature_scenes  # the glTF feature scenes of issue 18 (they import this module)
    for make in (cornell_box, cornell_spot, two_rooms, thin_wall, cornell_animated, cornell_light, open_sphere,
                 photometric_lamp, instanced_boxes, unlit_panel, clamped_texture) + feature_scenes.SCENES:
        make(out_dir)


if __name__ == "__main__":
    main()
