# Writes the open Blender scene as a slowlight scene: the meshes and their materials through the
# stock glTF exporter (a .glb beside the JSON), and in the JSON itself what glTF cannot carry or
# carries lossily: the camera and render resolution, every lamp in Blender's own watts (so no
# photometric/unitless question arises, and the sun keeps its angle), the volume as the medium,
# and the time window, emission and render settings of the panel. Everything that is not carried
# is returned as a warning line. Usable headless: write_scene(scene, folder).
#
# Coordinates: the glTF exporter's +Y up, glTF (x, y, z) = Blender (x, z, -y); one Blender unit
# is one metre (Cycles' convention; the exporter ignores the unit scale too).
import json
import math
import os

import bpy
from mathutils import Vector

from . import properties, volume

C_M_PER_NS = 0.299792458


def to_gltf(v):
    return [float(v[0]), float(v[2]), -float(v[1])]


def _axis(obj, local):
    return to_gltf((obj.matrix_world.to_3x3() @ Vector(local)).normalized())


def _rounded(values, digits=9):
    return [float("%.*g" % (digits, v)) for v in values]


def renderable(scene, view_layer=None):
    """The objects a render of this view layer draws (collections excluded from it are not)."""
    view_layer = view_layer or bpy.context.view_layer or scene.view_layers[0]
    return [o for o in view_layer.objects if not o.hide_render]


def _volume_output(tree, kind):
    if tree is None:
        return None
    outputs = [n for n in tree.nodes if n.bl_idname == kind]
    active = [n for n in outputs if getattr(n, "is_active_output", False)]
    return (active or outputs or [None])[0]


def _material_volume(mat):
    out = _volume_output(mat.node_tree if mat and mat.use_nodes else None, 'ShaderNodeOutputMaterial')
    return out.inputs["Volume"] if out and out.inputs["Volume"].is_linked else None


def _surface_check(mat, warnings):
    if mat is None or not mat.use_nodes:
        return
    out = _volume_output(mat.node_tree, 'ShaderNodeOutputMaterial')
    if out is None or not out.inputs["Surface"].is_linked:
        return
    node = out.inputs["Surface"].links[0].from_node
    if node.bl_idname not in ('ShaderNodeBsdfPrincipled', 'ShaderNodeEmission'):
        warnings.append("material %s: its surface shader %s is not a Principled BSDF or an Emission; "
                        "the glTF exporter writes an approximation" % (mat.name, node.bl_idname))


def bounds(objects):
    """World-space (glTF axes) bounding box of the objects' geometry and lamps."""
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for obj in objects:
        pts = [obj.matrix_world @ Vector(c) for c in obj.bound_box] if obj.type == 'MESH' \
            else [obj.matrix_world.translation]
        for p in pts:
            q = to_gltf(p)
            lo = [min(a, b) for a, b in zip(lo, q)]
            hi = [max(a, b) for a, b in zip(hi, q)]
    return lo, hi


def suggested_end_ns(scene):
    """Three crossings of the scene's diagonal, as slowlight gives a model rendered directly."""
    objs = [o for o in renderable(scene) if o.type in ('MESH', 'LIGHT', 'CAMERA')]
    if not objs:
        return None, None
    lo, hi = bounds(objs)
    diagonal = math.dist(lo, hi)
    return diagonal, 3 * diagonal / C_M_PER_NS


def _camera(scene, depsgraph, warnings):
    cam = scene.camera
    if cam is None or cam.type != 'CAMERA':
        raise RuntimeError("the scene has no active camera")
    r = scene.render
    width = max(1, r.resolution_x * r.resolution_percentage // 100)
    height = max(1, r.resolution_y * r.resolution_percentage // 100)
    data = cam.data
    if data.type != 'PERSP':
        warnings.append("camera %s: a %s camera is drawn as a perspective camera" % (cam.name, data.type.lower()))
    if abs(data.shift_x) > 1e-6 or abs(data.shift_y) > 1e-6:
        warnings.append("camera %s: lens shift is not carried" % cam.name)
    if data.dof.use_dof:
        warnings.append("camera %s: depth of field is not carried (a pinhole camera)" % cam.name)
    if abs(r.pixel_aspect_x - r.pixel_aspect_y) > 1e-6:
        warnings.append("render: non-square pixels are not carried")
    # The projection Blender renders with (sensor fit and aspect included): P[1][1] = 1/tan(vfov/2).
    proj = cam.calc_matrix_camera(depsgraph, x=width, y=height,
                                  scale_x=r.pixel_aspect_x, scale_y=r.pixel_aspect_y)
    vfov = 2 * math.degrees(math.atan(1.0 / proj[1][1]))
    pos = cam.matrix_world.translation
    return {"position": _rounded(to_gltf(pos)),
            "look_at": _rounded([a + b for a, b in zip(to_gltf(pos), _axis(cam, (0, 0, -1)))]),
            "up": _rounded(_axis(cam, (0, 1, 0))),
            "vfov_deg": float("%.9g" % vfov), "width": width, "height": height}


def _light(obj, warnings):
    L = obj.data
    colour = [float(c) for c in L.color]
    where = "lamp %s" % obj.name
    if L.use_nodes:
        warnings.append("%s: its node tree is not read (energy x colour only)" % where)
    pos = _rounded(to_gltf(obj.matrix_world.translation))
    if L.type in ('POINT', 'SPOT') and L.shadow_soft_size > 0:
        warnings.append("%s: radius %.3g m is not carried: drawn as a point (hard shadows)"
                        % (where, L.shadow_soft_size))
    if L.type == 'POINT':
        return {"type": "point", "position": pos, "power": _rounded([L.energy * c for c in colour])}
    if L.type == 'SPOT':
        # Blender's spot has a point light's intensity (P / 4 pi W/sr) inside its cone; slowlight's
        # spot spreads `power` over the cone, so power = P / 4 pi x 2 pi (1 - cos(half angle)).
        half = L.spot_size / 2
        if L.spot_blend > 0:
            warnings.append("%s: the cone's blend %.2f is not carried (a hard cone)" % (where, L.spot_blend))
        share = (1 - math.cos(half)) / 2
        return {"type": "spot", "position": pos, "direction": _rounded(_axis(obj, (0, 0, -1))),
                "cone_deg": float("%.9g" % min(max(math.degrees(L.spot_size), 0.1), 180)),
                "power": _rounded([L.energy * c * share for c in colour])}
    if L.type == 'SUN':
        return {"type": "sun", "direction": _rounded(_axis(obj, (0, 0, -1))),
                "angle_deg": float("%.9g" % min(math.degrees(L.angle), 45)),
                "irradiance": _rounded([L.energy * c for c in colour])}
    if L.type == 'AREA':
        sx = L.size * obj.scale[0]
        sy = (L.size_y if L.shape in ('RECTANGLE', 'ELLIPSE') else L.size) * obj.scale[1]
        if L.shape in ('DISK', 'ELLIPSE'):
            warnings.append("%s: a %s area light is drawn as the rectangle of the same area"
                            % (where, L.shape.lower()))
            sx, sy = sx * math.sqrt(math.pi) / 2, sy * math.sqrt(math.pi) / 2
        if L.spread < math.pi - 1e-4:
            warnings.append("%s: its spread is not carried (a Lambertian emitter)" % where)
        area = abs(sx * sy)
        # Blender's area light of P W emits from its -z side as a Lambertian surface: L = P / (pi A).
        radiance = [L.energy * c / (math.pi * area) for c in colour] if area > 0 else [0, 0, 0]
        m = obj.matrix_world.to_3x3().normalized()
        ex, ey = m @ Vector((sx, 0, 0)), m @ Vector((0, sy, 0))
        corner = obj.matrix_world.translation - ex / 2 - ey / 2
        # slowlight's quad light shines toward edge1 x edge2; (ey x ex) is the lamp's -z.
        return {"type": "quad", "corner": _rounded(to_gltf(corner)), "edge1": _rounded(to_gltf(ey)),
                "edge2": _rounded(to_gltf(ex)), "radiance": _rounded(radiance)}
    warnings.append("%s: a %s lamp is not carried" % (where, L.type))
    return None


def _medium_of(obj, warnings):
    for slot in obj.material_slots:
        sock = _material_volume(slot.material)
        if sock is not None:
            return volume.from_socket(sock, "volume %s (material %s)" % (obj.name, slot.material.name), warnings)
    return None


def _is_axis_box(obj):
    if obj.type != 'MESH' or len(obj.data.vertices) != 8:
        return False
    m = obj.matrix_world.to_3x3().normalized()
    return all(min(abs(m[i][j]), abs(abs(m[i][j]) - 1)) < 1e-5 for i in range(3) for j in range(3))


def _medium_json(m):
    s = _rounded(m.sigma_s)
    a = _rounded(m.sigma_a)
    out = {"sigma_s": s[0] if s[0] == s[1] == s[2] else s,
           "sigma_a": a[0] if a[0] == a[1] == a[2] else a}
    if m.g:
        out["g"] = float("%.6g" % min(max(m.g, -0.999), 0.999))
    return out


def _render_json(scene):
    st = scene.slowlight
    fps = scene.render.fps / scene.render.fps_base
    out = {
        "time": {"start_ns": st.start_ns, "end_ns": st.end_ns, "frames": properties.video_frames(scene),
                 "fps": int(round(fps)) if abs(fps - round(fps)) < 1e-6 else fps},
        "emission": {"mode": st.emission.lower()},
        "render": {"passes": st.passes, "photons_per_pass": st.photons, "camera_tof": st.camera_tof},
    }
    if st.emission == 'PULSE' and st.pulse_width_ns > 0:
        out["emission"]["width_ns"] = st.pulse_width_ns
    return out


def write_scene(scene, folder, depsgraph=None):
    """Writes folder/scene.json (and folder/scene.glb); returns (json path, warning lines)."""
    warnings = []
    depsgraph = depsgraph or bpy.context.evaluated_depsgraph_get()
    os.makedirs(folder, exist_ok=True)
    view_layer = getattr(depsgraph, "view_layer", None) or bpy.context.view_layer
    objs = renderable(scene, view_layer)
    if abs(scene.unit_settings.scale_length - 1.0) > 1e-9:
        warnings.append("units: the unit scale %g is not applied: one Blender unit is one metre "
                        "(as Cycles and the glTF exporter take it)" % scene.unit_settings.scale_length)

    doc = {"camera": _camera(scene, depsgraph, warnings)}

    # The medium: a mesh whose material has a Volume output, else the World's volume.
    media = []
    for obj in objs:
        if obj.type == 'MESH':
            m = _medium_of(obj, warnings)
            if m is not None:
                media.append((obj, m))
    volume_objects = {o for o, _ in media}
    medium = None
    if media:
        obj, m = media[0]
        for other, _ in media[1:]:
            warnings.append("volume %s: only one medium is carried (%s's); this one is left out"
                            % (other.name, obj.name))
        if not _is_axis_box(obj):
            warnings.append("volume %s: not an axis-aligned box; the medium fills its axis-aligned "
                            "bounding box" % obj.name)
        if any(s.material and s.material.use_nodes and _volume_output(s.material.node_tree, 'ShaderNodeOutputMaterial')
               and _volume_output(s.material.node_tree, 'ShaderNodeOutputMaterial').inputs["Surface"].is_linked
               for s in obj.material_slots):
            warnings.append("volume %s: its surface shader is not carried (only the volume)" % obj.name)
        lo, hi = bounds([obj])
        medium = _medium_json(m)
        medium["bounds"] = {"min": _rounded(lo), "max": _rounded(hi)}
    world = scene.world
    if world is not None and world.use_nodes:
        out = _volume_output(world.node_tree, 'ShaderNodeOutputWorld')
        if out is not None:
            wm = volume.from_socket(out.inputs["Volume"], "world %s" % world.name, warnings)
            if wm is not None and medium is not None:
                warnings.append("world %s: its volume is left out: the volume of %s is the medium"
                                % (world.name, media[0][0].name))
            elif wm is not None:
                # No bounds: slowlight fills the scene's bounding box (Cycles: all space).
                medium = _medium_json(wm)
            bg = [n for n in world.node_tree.nodes if n.bl_idname == 'ShaderNodeBackground']
            if out.inputs["Surface"].is_linked or bg:
                lit = any(n.inputs["Strength"].default_value > 0 and
                          max(n.inputs["Color"].default_value[:3]) > 0 or n.inputs["Color"].is_linked
                          for n in bg)
                if lit:
                    warnings.append("world %s: its background light is not carried (slowlight has no sky)"
                                    % world.name)
    elif world is not None and max(world.color) > 0:
        warnings.append("world %s: its background light is not carried (slowlight has no sky)" % world.name)
    if medium is not None and medium_is_empty(medium):
        warnings.append("the medium's coefficients are all zero: no medium written")
        medium = None
    if medium is not None:
        doc["medium"] = medium

    lights = []
    for obj in objs:
        if obj.type == 'LIGHT':
            j = _light(obj, warnings)
            if j is not None:
                lights.append(j)
    doc["lights"] = lights

    # Meshes and their materials through glTF: every renderable object but the volume boxes.
    export = [o for o in objs if o.type in ('MESH', 'CURVE', 'SURFACE', 'META', 'FONT')
              and o not in volume_objects]
    for o in objs:
        if o.type not in ('MESH', 'CURVE', 'SURFACE', 'META', 'FONT', 'LIGHT', 'CAMERA', 'EMPTY') \
                and o not in volume_objects:
            warnings.append("object %s: a %s object is not carried" % (o.name, o.type.lower()))
    for o in export:
        for slot in o.material_slots:
            _surface_check(slot.material, warnings)
    doc["shapes"] = []
    if export:
        glb = os.path.join(folder, "scene.glb")
        _export_glb(export, glb, view_layer)
        doc["shapes"].append(_gltf_shape("scene.glb"))
    doc.update(_render_json(scene))
    path = os.path.join(folder, "scene.json")
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
    return path, warnings


def _gltf_shape(name):
    # Blender 3.x's Principled BSDF (v1) adds its diffuse base under the specular layer without
    # taking the layer's share, which Cycles renders as it is: "blender3" draws it the same way
    # (uncapped), so that the render matches Cycles'. 4.x's Principled v2 conserves energy, as
    # slowlight's default does (docs/materials.md, "Two choices of base").
    shape = {"type": "gltf", "file": name}
    if bpy.app.version < (4, 0, 0):
        shape["principled"] = "blender3"
    return shape


def medium_is_empty(medium):
    vals = []
    for k in ("sigma_s", "sigma_a"):
        v = medium.get(k, 0)
        vals += v if isinstance(v, list) else [v]
    return max(vals) <= 0


def _export_glb(objects, path, view_layer):
    before = {o.name: o.select_get() for o in view_layer.objects}
    active = view_layer.objects.active
    try:
        for o in view_layer.objects:
            o.select_set(o in objects)
        # Lamps and the camera are written by the JSON itself (in Blender's watts; the sun's angle).
        bpy.ops.export_scene.gltf(filepath=path, export_format='GLB', use_selection=True,
                                  export_cameras=False, export_lights=False, export_apply=True,
                                  export_yup=True, export_animations=False, export_draco_mesh_compression_enable=False)
    finally:
        for o in view_layer.objects:
            o.select_set(before.get(o.name, False))
        view_layer.objects.active = active
