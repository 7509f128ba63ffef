"""glTF feature scenes for issue 18, written by make_scenes.py (which imports this module): one
small scene per material or geometry feature, each checked by a test against numbers derived
here. Unlit panels (KHR_materials_unlit) show their base colour as radiance, so a pixel's
expected value is exact; the normal-mapped plane is lit by a sun.
"""
import math
import struct

from make_scenes import Gltf, Part, png_rgba

# glTF sampler constants.
NEAREST, LINEAR, LINEAR_MIPMAP_LINEAR = 9728, 9729, 9987
REPEAT, CLAMP = 10497, 33071


def embed_png(g, name, width, height, rows):
    """Adds a PNG image to the buffer; returns its image index."""
    png = png_rgba(width, height, rows)
    while len(g.bin) % 4:
        g.bin.append(0)
    g.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(g.bin), "byteLength": len(png)})
    g.bin += png
    images = g.doc.setdefault("images", [])
    images.append({"name": name, "mimeType": "image/png", "bufferView": len(g.doc["bufferViews"]) - 1})
    return len(images) - 1


def texture(g, image, sampler):
    """A texture of `image` with a new sampler (a dict of glTF sampler fields)."""
    samplers = g.doc.setdefault("samplers", [])
    samplers.append(sampler)
    textures = g.doc.setdefault("textures", [])
    textures.append({"source": image, "sampler": len(samplers) - 1})
    return len(textures) - 1


def unlit(g, name, color, texture_info=None, alpha_mode=None):
    m = g.material(name, color)
    g.doc["materials"][m]["extensions"] = {"KHR_materials_unlit": {}}
    g.extensions.add("KHR_materials_unlit")
    if texture_info is not None:
        g.doc["materials"][m]["pbrMetallicRoughness"]["baseColorTexture"] = texture_info
    if alpha_mode:
        g.doc["materials"][m]["alphaMode"] = alpha_mode
    return m


def panel(material, x0, x1, y0, y1, z=0.0):
    """A rectangle facing +Z with u = 0..1 left to right and v = 0..1 top to bottom (glTF's v
    runs down the image)."""
    p = Part(material)
    p.rect(2, z, 1, (x0, y0), (x1, y1))
    p.uvs = [[(q[0] - x0) / (x1 - x0), (y1 - q[1]) / (y1 - y0)] for q in p.positions]
    return p


def int_accessor(g, values, kind, fmt, component_type):
    """A normalised integer vertex accessor (struct format `fmt` per component)."""
    flat = [x for v in values for x in v]
    data = struct.pack("<%d%s" % (len(flat), fmt), *flat)
    g.doc["accessors"].append({"bufferView": g._view(data, 34962), "componentType": component_type,
                               "normalized": True, "count": len(values), "type": kind})
    return len(g.doc["accessors"]) - 1


def prim(g, mesh, i):
    return g.doc["meshes"][mesh]["primitives"][i]


# vertex_colors: (left edge, right edge) colours of each 3 m panel, top to bottom, as linear
# floats; the middle panel's are unorm8 RGBA codes, the bottom one's unorm16 RGB codes.
VERTEX_COLORS = [((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
                 ((0.0, 1.0, 0.2), (1.0, 0.4, 0.0)),
                 ((0.2, 0.4, 0.6), (0.8, 0.6, 0.4))]


def vertex_colors(out_dir):
    """Three unlit 3 x 1 m panels stacked in y (top y in [0.5, 1.5]) whose COLOR_0 runs from the
    left colour to the right one of VERTEX_COLORS: float VEC3 (top), unorm8 VEC4 (middle),
    unorm16 VEC3 (bottom). Base colour factor white, so a pixel's radiance is the interpolated
    vertex colour: at image column x of 96, mix(left, right, (x + 0.5) / 96). The camera 3 m in
    front sees the 3 x 3 m square edge to edge. No light, no sidecar."""
    g = Gltf("vertex_colors")
    m = unlit(g, "VertexColored", [1.0, 1.0, 1.0, 1.0])
    parts = [panel(m, -1.5, 1.5, 0.5 - k, 1.5 - k) for k in range(3)]
    mesh = g.mesh("Panels", parts)
    for k, part in enumerate(parts):
        left, right = VERTEX_COLORS[k]
        colors = [left if q[0] < 0 else right for q in part.positions]
        attrs = prim(g, mesh, k)["attributes"]
        if k == 0:
            attrs["COLOR_0"] = g._accessor([list(c) for c in colors], "VEC3")
        elif k == 1:
            codes = [[round(255 * x) for x in c] + [255] for c in colors]
            attrs["COLOR_0"] = int_accessor(g, codes, "VEC4", "B", 5121)
        else:
            codes = [[round(65535 * x) for x in c] for c in colors]
            attrs["COLOR_0"] = int_accessor(g, codes, "VEC3", "H", 5123)
    g.node({"name": "Panels", "mesh": mesh})
    g.camera("Camera", [0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 2.0 * math.atan(0.5))
    g.write(out_dir, None)


# texture_transform: the 2 x 2 texture's texels, [row][column], row 0 at the top (v < 0.5).
QUADRANTS = [[(255, 0, 0, 255), (0, 255, 0, 255)], [(0, 0, 255, 255), (255, 255, 255, 255)]]


def texture_transform(out_dir):
    """Four unlit 1 x 1 m panels in a row (x from -2 to 2) showing a 2 x 2 texture (QUADRANTS:
    red, green / blue, white) with NEAREST filters, each through another texture coordinate:
      0: TEXCOORD_1 (TEXCOORD_0 is (0.75, 0.75) everywhere, the white texel);
      1: KHR_texture_transform offset (0.5, 0): u' = u + 0.5 (columns swap, REPEAT);
      2: rotation pi/2 with offset (0, 1): (u', v') = (v, 1 - u) (the matrix
         [[cos, sin], [-sin, cos]]: counter-clockwise with v down, as the extension's text and
         Khronos's TextureTransformTest have it);
      3: scale (2, 2) with the extension's texCoord 1 overriding the texture info's 0.
    KHR_texture_transform is required. The camera 2 m in front sees the 4 x 1 m row in a 4:1
    image. No light, no sidecar."""
    g = Gltf("texture_transform")
    image = embed_png(g, "Quadrants", 2, 2, QUADRANTS)
    tex = texture(g, image, {"magFilter": NEAREST, "minFilter": NEAREST, "wrapS": REPEAT, "wrapT": REPEAT})
    ext = "KHR_texture_transform"
    infos = [{"index": tex, "texCoord": 1},
             {"index": tex, "extensions": {ext: {"offset": [0.5, 0.0]}}},
             {"index": tex, "extensions": {ext: {"rotation": math.pi / 2, "offset": [0.0, 1.0]}}},
             {"index": tex, "texCoord": 0, "extensions": {ext: {"scale": [2.0, 2.0], "texCoord": 1}}}]
    parts = []
    for k, info in enumerate(infos):
        parts.append(panel(unlit(g, "Transform%d" % k, [1.0, 1.0, 1.0, 1.0], info), -2.0 + k, -1.0 + k, -0.5, 0.5))
    mesh = g.mesh("Panels", parts)
    for k, part in enumerate(parts):
        if k in (0, 3):  # the texture reads set 1; set 0 points at the white texel
            prim(g, mesh, k)["attributes"]["TEXCOORD_1"] = g._accessor(part.uvs, "VEC2")
            prim(g, mesh, k)["attributes"]["TEXCOORD_0"] = g._accessor([[0.75, 0.75]] * len(part.uvs), "VEC2")
    g.extensions.add(ext)
    g.doc["extensionsRequired"] = [ext]
    g.node({"name": "Panels", "mesh": mesh})
    g.camera("Camera", [0.0, 0.0, 2.0], [0.0, 0.0, 0.0], 2.0 * math.atan(0.25))
    g.write(out_dir, None)


def texture_filters(out_dir):
    """Two unlit 1 x 1 m panels side by side (x from -1 to 1) showing a 2 x 1 texture, red left
    and blue right, magnified 16 times with CLAMP_TO_EDGE: the left panel's sampler is NEAREST
    (a hard edge at u = 0.5), the right one's LINEAR (blue weight (u - 0.25) / 0.5 between the
    texel centres, filtered in linear space). At panel column c of 32: u = (c + 0.5) / 32. The
    camera 2 m in front sees both in a 2:1 image. No light, no sidecar."""
    g = Gltf("texture_filters")
    image = embed_png(g, "RedBlue", 2, 1, [[(255, 0, 0, 255), (0, 0, 255, 255)]])
    nearest = texture(g, image, {"magFilter": NEAREST, "minFilter": NEAREST, "wrapS": CLAMP, "wrapT": CLAMP})
    linear = texture(g, image, {"magFilter": LINEAR, "minFilter": LINEAR_MIPMAP_LINEAR, "wrapS": CLAMP,
                                "wrapT": CLAMP})
    parts = [panel(unlit(g, "Nearest", [1.0, 1.0, 1.0, 1.0], {"index": nearest}), -1.0, 0.0, -0.5, 0.5),
             panel(unlit(g, "Linear", [1.0, 1.0, 1.0, 1.0], {"index": linear}), 0.0, 1.0, -0.5, 0.5)]
    g.node({"name": "Panels", "mesh": g.mesh("Panels", parts)})
    g.camera("Camera", [0.0, 0.0, 2.0], [0.0, 0.0, 0.0], 2.0 * math.atan(0.25))
    g.write(out_dir, None)


# normal_map_plane: the tangent-space normal each panel's 1 x 1 normal map holds (RGB codes):
# tilted 30 degrees toward the image's up (+Y, green > 128) on the left, down on the right.
NORMAL_UP = (128, 191, 238)
NORMAL_DOWN = (128, 64, 238)
SUN_IRRADIANCE = 3.0  # W/m^2 (written in lux: 683 lm/W)


def normal_map_plane(out_dir):
    """Two grey 1 x 1 m panels facing +Z (x from -1 to 1), rough dielectric, with normal maps and
    no TANGENT attribute, so the loader generates MikkTSpace tangents: glTF's normal-map +Y is up
    in the image, which on these panels (v down the image, +Y up in the world) is world +Y. The
    sun shines from above and in front (travelling along (0, -1, -1) / sqrt 2, 3 W/m^2): the
    left panel, whose normals tilt up, is lit at cos 0.966 and the right at cos 0.259, so the
    left is brighter (a flipped bitangent would swap them). The camera 2 m in front sees both in
    a 2:1 image."""
    g = Gltf("normal_map_plane")
    parts = []
    for k, code in enumerate((NORMAL_UP, NORMAL_DOWN)):
        image = embed_png(g, "Normal%d" % k, 1, 1, [[code + (255,)]])
        tex = texture(g, image, {"magFilter": LINEAR, "minFilter": LINEAR, "wrapS": REPEAT, "wrapT": REPEAT})
        m = g.material("Grey%d" % k, [0.8, 0.8, 0.8, 1.0], roughness=1.0)
        g.doc["materials"][m]["normalTexture"] = {"index": tex}
        parts.append(panel(m, -1.0 + k, float(k), -0.5, 0.5))
    g.node({"name": "Panels", "mesh": g.mesh("Panels", parts)})
    sun = g.light({"name": "Sun", "type": "directional", "intensity": SUN_IRRADIANCE * 683.0})
    s = math.sin(math.radians(-22.5))
    c = math.cos(math.radians(-22.5))
    g.node({"name": "Sun", "translation": [0.0, 3.0, 3.0], "rotation": [s, 0.0, 0.0, c],
            "extensions": {"KHR_lights_punctual": {"light": sun}}})  # -Z turned -45 deg about X
    g.camera("Camera", [0.0, 0.0, 2.0], [0.0, 0.0, 0.0], 2.0 * math.atan(0.25))
    g.write(out_dir, None)


# blend_panels: an opaque unlit background and two unlit BLEND panels in front of it.
BLEND_BACKGROUND = (0.2, 0.4, 0.8)
BLEND_NEAR = ((1.0, 0.0, 0.0), 0.25)  # colour, alpha
BLEND_FAR = ((0.0, 1.0, 0.0), 0.5)


def blend_panels(out_dir):
    """An opaque unlit 3 x 1 m background (BLEND_BACKGROUND) at z = 0 and, in front, two unlit
    BLEND panels: a red one of alpha 0.25 at z = 1 (x from -1.2 to 1/3, covering the left and
    middle thirds of the image) and a green one of alpha 0.5 at z = 0.5 (x from -0.42 to 0.42,
    the middle third). The near panel comes first in the file, so drawing in file order would
    blend the far one over it. Expected radiance: left third 0.25 red + 0.75 background; middle
    0.25 red + 0.75 (0.5 green + 0.5 background); right the background. The camera at z = 3
    sees the background edge to edge in a 3:1 image. No light, no sidecar."""
    write_blend_panels(out_dir, "blend_panels", unlit)


def blend_panels_lit(out_dir):
    """blend_panels with lit (rough dielectric) materials under ddish's default sky: the panels
    are shaded by the probes, and the probes behind a single-sided blended panel must see
    through its back (the rasterizer culls it) for the panel to be lit as the reference lights
    it."""
    def lit(g, name, color, texture_info=None, alpha_mode=None):
        m = g.material(name, color)
        if alpha_mode:
            g.doc["materials"][m]["alphaMode"] = alpha_mode
        return m
    write_blend_panels(out_dir, "blend_panels_lit", lit)


def write_blend_panels(out_dir, name, make_material):
    g = Gltf(name)
    (near_color, near_alpha), (far_color, far_alpha) = BLEND_NEAR, BLEND_FAR
    near = make_material(g, "NearRed", list(near_color) + [near_alpha], alpha_mode="BLEND")
    far = make_material(g, "FarGreen", list(far_color) + [far_alpha], alpha_mode="BLEND")
    back = make_material(g, "Background", list(BLEND_BACKGROUND) + [1.0])
    g.node({"name": "Near", "mesh": g.mesh("Near", [panel(near, -1.2, 1.0 / 3.0, -0.4, 0.4, 1.0)])})
    g.node({"name": "Far", "mesh": g.mesh("Far", [panel(far, -0.42, 0.42, -0.45, 0.45, 0.5)])})
    g.node({"name": "Background", "mesh": g.mesh("Background", [panel(back, -1.5, 1.5, -0.5, 0.5)])})
    g.camera("Camera", [0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 2.0 * math.atan(1.0 / 6.0))
    g.write(out_dir, None)


# dielectric_panels: the four black panels' dielectric layers, left to right.
DIELECTRIC_ROUGHNESS = 0.7
DIELECTRIC_SUN = 3.0  # W/m^2 (written in lux), travelling along -Z: head-on
DIELECTRICS = [
    ("Default", None, None),                                     # F0 0.04, weight 1
    ("Ior2", {"ior": 2.0}, None),                                # F0 (1/3)^2 = 1/9
    ("Weight", None, {"specularFactor": 0.5}),                   # F0 0.04, weight 0.5
    ("Colored", None, {"specularColorFactor": [1.0, 0.5, 0.25]}),  # F0 0.04 (1, 0.5, 0.25)
]


def dielectric_panels(out_dir):
    """Four black (base colour 0), rough (0.7) dielectric 0.5 x 0.5 m panels in a row facing +Z
    (x from -1 to 1), under a sun shining head-on (along -Z, 3 W/m^2): with no diffuse base, a
    pixel's radiance is the specular lobe alone, F D V E with the analytic GGX terms, and F's F0
    is each panel's: glTF's 0.04, KHR_materials_ior 2 (1/9), KHR_materials_specular weight 0.5,
    and specular colour (1, 0.5, 0.25). The camera 4 m in front sees the row in a 4:1 image
    (half-height 0.25 m: yfov 2 atan(1/16))."""
    g = Gltf("dielectric_panels")
    parts = []
    for k, (name, ior, specular) in enumerate(DIELECTRICS):
        m = g.material(name, [0.0, 0.0, 0.0, 1.0], roughness=DIELECTRIC_ROUGHNESS)
        ext = {}
        if ior:
            ext["KHR_materials_ior"] = ior
        if specular:
            ext["KHR_materials_specular"] = specular
        if ext:
            g.doc["materials"][m]["extensions"] = ext
            g.extensions.update(ext.keys())
        parts.append(panel(m, -1.0 + 0.5 * k, -0.5 + 0.5 * k, -0.25, 0.25))
    g.node({"name": "Panels", "mesh": g.mesh("Panels", parts)})
    sun = g.light({"name": "Sun", "type": "directional", "intensity": DIELECTRIC_SUN * 683.0})
    g.node({"name": "Sun", "translation": [0.0, 0.0, 5.0], "extensions": {"KHR_lights_punctual": {"light": sun}}})
    g.camera("Camera", [0.0, 0.0, 4.0], [0.0, 0.0, 0.0], 2.0 * math.atan(1.0 / 16.0))
    g.write(out_dir, None)


# environment_plane: a Lambertian floor for image-based lighting (--environment).
ENVIRONMENT_PLANE_ALBEDO = 0.5


def environment_plane(out_dir):
    """A 4 x 4 m floor at y = 0 facing +Y, base colour ENVIRONMENT_PLANE_ALBEDO, rough, with
    KHR_materials_specular's specularFactor 0: no dielectric layer, so it is exactly Lambertian
    in both renderers and its radiance is albedo x irradiance / pi. No light: the tests light it
    with --environment maps they write (tests/app/environment_cli_test.cpp). The camera 0.5 m
    above the floor looks horizontally along -Z with a 60 degree field: the image's upper half is
    sky, its lower quarter floor."""
    g = Gltf("environment_plane")
    a = ENVIRONMENT_PLANE_ALBEDO
    m = g.material("Lambert", [a, a, a, 1.0], roughness=1.0)
    g.doc["materials"][m]["extensions"] = {"KHR_materials_specular": {"specularFactor": 0.0}}
    g.extensions.add("KHR_materials_specular")
    p = Part(m)
    p.rect(1, 0.0, 1, (-2.0, -2.0), (2.0, 2.0))
    g.node({"name": "Floor", "mesh": g.mesh("Floor", [p])})
    g.camera("Camera", [0.0, 0.5, 1.5], [0.0, 0.5, 0.0], math.radians(60.0))
    g.write(out_dir, None)


# blend_shadow: a BLEND panel between a sun and a Lambertian floor.
BLEND_SHADOW_ALBEDO = 0.5
BLEND_SHADOW_ALPHA = 0.5
BLEND_SHADOW_SUN = 2.0  # W/m^2 (written in lux), straight down


def blend_shadow(out_dir):
    """A 4 x 4 m Lambertian floor (albedo BLEND_SHADOW_ALBEDO, specularFactor 0) at y = 0 under a
    sun shining straight down (BLEND_SHADOW_SUN W/m^2), and 1 m above it a 1 x 1 m black,
    double-sided BLEND panel (x, z from -0.5 to 0.5, alpha BLEND_SHADOW_ALPHA): both renderers
    treat alpha as coverage, so the floor under the panel receives (1 - alpha) of the sun,
    radiance albedo / pi * E * (1 - alpha), and the floor beyond its shadow albedo / pi * E.
    Nothing else lights the floor: no sky (the scene has a light), and the black panel (no
    dielectric layer) reflects nothing. The camera at (0, 0.6, 2.5) looks at the origin (40
    degree field): the image centre is the floor under the panel's centre."""
    g = Gltf("blend_shadow")
    a = BLEND_SHADOW_ALBEDO
    floor = g.material("Floor", [a, a, a, 1.0], roughness=1.0)
    panel_m = g.material("Panel", [0.0, 0.0, 0.0, BLEND_SHADOW_ALPHA], roughness=1.0)
    g.doc["materials"][panel_m]["alphaMode"] = "BLEND"
    g.doc["materials"][panel_m]["doubleSided"] = True
    for m in (floor, panel_m):
        g.doc["materials"][m]["extensions"] = {"KHR_materials_specular": {"specularFactor": 0.0}}
    g.extensions.add("KHR_materials_specular")
    f = Part(floor)
    f.rect(1, 0.0, 1, (-2.0, -2.0), (2.0, 2.0))
    p = Part(panel_m)
    p.rect(1, 1.0, 1, (-0.5, -0.5), (0.5, 0.5))
    g.node({"name": "Floor", "mesh": g.mesh("Floor", [f])})
    g.node({"name": "Panel", "mesh": g.mesh("Panel", [p])})
    sun = g.light({"name": "Sun", "type": "directional", "intensity": BLEND_SHADOW_SUN * 683.0})
    s = math.sqrt(0.5)  # -90 degrees about X: the node's -Z (where the light travels) becomes -Y
    g.node({"name": "Sun", "translation": [0.0, 5.0, 0.0], "rotation": [-s, 0.0, 0.0, s],
            "extensions": {"KHR_lights_punctual": {"light": sun}}})
    g.camera("Camera", [0.0, 0.6, 2.5], [0.0, 0.0, 0.0], math.radians(40.0))
    g.write(out_dir, None)


def draco_box(out_dir):
    """A 1 m cube of base colour (0.8, 0.5, 0.3) with normals and UVs, no camera (the framing
    camera sees it) and no light (the default sky lights it): the plain twin of
    draco_box_draco.gltf, which scripts/make_draco_box.sh writes from it with Draco's encoder
    (whose glTF writer drops cameras: with none, both twins are framed alike)."""
    g = Gltf("draco_box")
    m = g.material("Clay", [0.8, 0.5, 0.3, 1.0], roughness=0.6)
    p = Part(m)
    p.box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
    g.node({"name": "Box", "mesh": g.mesh("Box", [p])})
    g.write(out_dir, None)


def raw_accessor(g, values, kind, fmt, component_type, normalized=False):
    """A vertex accessor of integers (struct format `fmt` per component), normalised or not."""
    flat = [x for v in values for x in v]
    data = struct.pack("<%d%s" % (len(flat), fmt), *flat)
    acc = {"bufferView": g._view(data, 34962), "componentType": component_type,
           "count": len(values), "type": kind}
    if normalized:
        acc["normalized"] = True
    g.doc["accessors"].append(acc)
    return len(g.doc["accessors"]) - 1


def animate(g, name, node, path, times, values, kind):
    """An animation of one channel: `values` (one list per key, or scalars for weights)."""
    t = g._times(times)
    v = g._accessor(values, kind)
    g.doc.setdefault("animations", []).append({
        "name": name,
        "samplers": [{"input": t, "output": v, "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"node": node, "path": path}}]})


# skinned_bar: a 0.2 x 2 x 0.2 m grey bar standing on the origin (x, z in [-0.1, 0.1], y in
# [0, 2]) in two rigid halves, the lower skinned to joint Root (at the origin), the upper to
# joint Elbow (at y = 1, a child of Root). Elbow turns about +Z from 0 to 90 degrees over
# 1 s, so at t >= 1 the upper half points along -x: the posed bar's bounds are x in [-1, 0.1],
# y in [0, 1.1], z in [-0.1, 0.1]. The mesh's own node stands at x = 3: glTF ignores a skinned
# mesh's node transform, so it must not move the bar.
SKINNED_BAR_BENT = ((-1.0, 0.0, -0.1), (0.1, 1.1, 0.1))


def skinned_bar(out_dir):
    """A camera 6 m in front of the bent bar's middle sees it in a 4:3 view 3.2 m wide at the
    bar (22.6 degree field); no light: the default sky lights it, as sky_coverage.h expects."""
    g = Gltf("skinned_bar")
    grey = g.material("Grey", [0.5, 0.5, 0.5, 1.0])
    lower, upper = Part(grey), Part(grey)
    lower.box((-0.1, 0.0, -0.1), (0.1, 1.0, 0.1))
    upper.box((-0.1, 1.0, -0.1), (0.1, 2.0, 0.1))
    bar = Part(grey)
    for part in (lower, upper):
        base = len(bar.positions)
        bar.positions += part.positions
        bar.normals += part.normals
        bar.uvs += part.uvs
        bar.indices += [base + i for i in part.indices]
    mesh = g.mesh("Bar", [bar])
    attrs = prim(g, mesh, 0)["attributes"]
    joints = [[0, 0, 0, 0]] * len(lower.positions) + [[1, 0, 0, 0]] * len(upper.positions)
    attrs["JOINTS_0"] = raw_accessor(g, joints, "VEC4", "B", 5121)
    attrs["WEIGHTS_0"] = g._accessor([[1.0, 0.0, 0.0, 0.0]] * len(bar.positions), "VEC4")
    elbow = g.node({"name": "Elbow", "translation": [0.0, 1.0, 0.0]}, root=False)
    root = g.node({"name": "Root", "children": [elbow]})
    # Inverse bind matrices (column-major): Root's is the identity, Elbow's moves y = 1 to 0.
    ibm = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]
    data = struct.pack("<32f", *ibm)
    while len(g.bin) % 4:
        g.bin.append(0)
    g.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(g.bin), "byteLength": len(data)})
    g.bin += data
    g.doc["accessors"].append({"bufferView": len(g.doc["bufferViews"]) - 1,
                               "componentType": 5126, "count": 2, "type": "MAT4"})
    g.doc["skins"] = [{"name": "BarSkin", "joints": [root, elbow],
                       "inverseBindMatrices": len(g.doc["accessors"]) - 1}]
    g.node({"name": "Bar", "mesh": mesh, "skin": 0, "translation": [3.0, 0.0, 0.0]})
    s = math.sqrt(0.5)
    animate(g, "Bend", elbow, "rotation", [0.0, 1.0], [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, s, s]], "VEC4")
    g.camera("Camera", [-0.45, 1.0, 6.0], [-0.45, 1.0, 0.0], 2.0 * math.atan(0.2))
    g.write(out_dir, None)


# morph_panels: two unlit 1 x 1 m panels of MORPH_COLOR facing +Z, one mesh with one morph
# target that lifts the top edge by 1 m (POSITION delta) and tips the normal towards +Y (NORMAL
# delta (0, 2, 0)). The left panel (x in [-0.5, 0.5]) keeps the mesh's default weight 0.5: its
# top edge is at y = 1.5. The right one (x in [1, 2]) has a "weights" channel from 0 at t = 0
# to 1 at t = 2 s (LINEAR): at t = 1 its top edge is at 1.5, at t = 0.5 at 1.25.
MORPH_COLOR = [0.2, 0.6, 0.9]


def morph_panels(out_dir):
    """The camera 4 m in front of (0.75, 0.9) sees both panels in a 4:3 view 2.4 m high (33.4
    degree field): 40 px per metre at 128 x 96. No light, no sidecar."""
    g = Gltf("morph_panels")
    m = unlit(g, "MorphUnlit", MORPH_COLOR + [1.0])
    p = panel(m, -0.5, 0.5, 0.0, 1.0)
    mesh = g.mesh("Panel", [p])
    lift = [[0.0, 1.0 if q[1] > 0.5 else 0.0, 0.0] for q in p.positions]
    tip = [[0.0, 2.0, 0.0] for _ in p.positions]
    prim(g, mesh, 0)["targets"] = [{"POSITION": g._accessor(lift, "VEC3", True),
                                    "NORMAL": g._accessor(tip, "VEC3")}]
    g.doc["meshes"][mesh]["weights"] = [0.5]
    g.node({"name": "Default", "mesh": mesh})
    right = g.node({"name": "Animated", "mesh": mesh, "translation": [1.5, 0.0, 0.0]})
    animate(g, "Lift", right, "weights", [0.0, 2.0], [0.0, 1.0], "SCALAR")
    g.camera("Camera", [0.75, 0.9, 4.0], [0.75, 0.9, 0.0], 2.0 * math.atan(0.3))
    g.write(out_dir, None)


SCENES = (vertex_colors, texture_transform, texture_filters, normal_map_plane, blend_panels, blend_panels_lit,
          dielectric_panels, environment_plane, draco_box, skinned_bar, morph_panels, blend_shadow)
