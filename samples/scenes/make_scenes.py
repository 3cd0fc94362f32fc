#!/usr/bin/python3
"""Writes the sample scenes of samples/scenes/: a Cornell-style closed box, two rooms joined by a door
with sunlight through a window (also as a glTF 2.0 file, two_rooms.gltf), and a long flat outdoor strip
(a race track) with a flat probe set. Run it from anywhere; it rewrites the .json, .obj and .gltf files
next to itself. Units are metres, +y is up."""

import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def quad(vertices, indices, a, b, c, d):
    """Adds the quad a-b-c-d (counter-clockwise seen from the side its normal points to)."""
    base = len(vertices)
    vertices.extend([a, b, c, d])
    indices.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]])


def box(vertices, indices, lo, hi, inward):
    """Adds the six faces of an axis-aligned box, normals pointing in or out."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = [
        [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],  # -x, outward
        [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],  # +x
        [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],  # -y
        [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],  # +y
        [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],  # -z
        [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],  # +z
    ]
    for f in faces:
        quad(vertices, indices, *(reversed(f) if inward else f))


def wall_with_holes(vertices, indices, axis_x, y_range, z_range, holes, facing_positive):
    """A wall in the plane x = axis_x over y_range x z_range, minus rectangular holes
    [(y0, y1, z0, z1)], cut into rectangles along z then y. One-sided, facing +x or -x."""
    ys = sorted({y_range[0], y_range[1]} | {h[0] for h in holes} | {h[1] for h in holes})
    zs = sorted({z_range[0], z_range[1]} | {h[2] for h in holes} | {h[3] for h in holes})
    for i in range(len(ys) - 1):
        for j in range(len(zs) - 1):
            yc, zc = (ys[i] + ys[i + 1]) / 2, (zs[j] + zs[j + 1]) / 2
            if any(h[0] < yc < h[1] and h[2] < zc < h[3] for h in holes):
                continue
            a = (axis_x, ys[i], zs[j])
            b = (axis_x, ys[i + 1], zs[j])
            c = (axis_x, ys[i + 1], zs[j + 1])
            d = (axis_x, ys[i], zs[j + 1])
            quad(vertices, indices, *((a, b, c, d) if facing_positive else (d, c, b, a)))


def write_obj(name, vertices, indices, comment):
    with open(os.path.join(HERE, name), "w") as f:
        f.write("# %s (written by make_scenes.py)\n" % comment)
        for v in vertices:
            f.write("v %.6g %.6g %.6g\n" % v)
        for t in indices:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def quaternion_from_minus_z(direction):
    """The unit quaternion [x, y, z, w] turning glTF's light direction (0, 0, -1) onto direction."""
    length = math.sqrt(sum(c * c for c in direction))
    dx, dy, dz = (c / length for c in direction)
    # The half-way rotation: (a x b, 1 + a . b) normalised, with a = (0, 0, -1) and b = the direction.
    q = [dy, -dx, 0.0, 1.0 - dz]
    norm = math.sqrt(sum(c * c for c in q))
    return [c / norm for c in q]


def write_gltf(name, meshes, lights, comment):
    """A glTF 2.0 file with one embedded buffer: meshes [(name, vertices, triangles, albedo)] as
    one-sided PBR materials (baseColorFactor = albedo), lights [(name, KHR_lights_punctual light, node
    translation or None, direction or None)] placed by nodes."""
    data = b""
    accessors, views, gltf_meshes, materials, nodes = [], [], [], [], []
    for mesh_name, vertices, triangles, albedo in meshes:
        positions = struct.pack("<%df" % (3 * len(vertices)), *[c for v in vertices for c in v])
        indices = struct.pack("<%dI" % (3 * len(triangles)), *[k for t in triangles for k in t])
        for payload, kind, component, count in ((positions, "VEC3", 5126, len(vertices)),
                                                (indices, "SCALAR", 5125, 3 * len(triangles))):
            views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(payload)})
            accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
            if kind == "VEC3":
                accessor["min"] = [min(float(v[a]) for v in vertices) for a in range(3)]
                accessor["max"] = [max(float(v[a]) for v in vertices) for a in range(3)]
            accessors.append(accessor)
            data += payload
        materials.append({"name": mesh_name, "pbrMetallicRoughness": {"baseColorFactor": list(albedo) + [1.0],
                                                                      "metallicFactor": 0.0}})
        gltf_meshes.append({"name": mesh_name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                                "indices": len(accessors) - 1,
                                                                "material": len(materials) - 1}]})
        nodes.append({"name": mesh_name, "mesh": len(gltf_meshes) - 1})
    gltf_lights = []
    for light_name, light, position, direction in lights:
        gltf_lights.append(dict(light, name=light_name))
        node = {"name": light_name, "extensions": {"KHR_lights_punctual": {"light": len(gltf_lights) - 1}}}
        if position is not None:
            node["translation"] = list(position)
        if direction is not None:
            node["rotation"] = quaternion_from_minus_z(direction)
        nodes.append(node)
    gltf = {
        "asset": {"version": "2.0", "generator": "tetprobe samples/scenes/make_scenes.py: " + comment},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": gltf_lights}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gltf_meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")}],
    }
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def grid(lo, hi, counts):
    points = []
    for k in range(counts[2]):
        for j in range(counts[1]):
            for i in range(counts[0]):
                p = []
                for axis, step in enumerate((i, j, k)):
                    n = counts[axis]
                    p.append(round(lo[axis] + (hi[axis] - lo[axis]) * (step / (n - 1) if n > 1 else 0.0), 4))
                points.append(p)
    return points


def write_json(name, scene):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


def cornell_box():
    # A closed 2 m box: white floor, ceiling and back wall, red left wall, green right wall, a
    # square emissive panel under the ceiling, two white blocks; probes on a 4 x 4 x 4 lattice.
    white, red, green = [0.73, 0.73, 0.73], [0.65, 0.05, 0.05], [0.12, 0.45, 0.15]
    meshes = []

    def quad_mesh(name, corners, albedo, emission=None):
        v, i = [], []
        quad(v, i, *corners)
        m = {"name": name, "vertices": [list(p) for p in v], "indices": i, "material": {"albedo": albedo}}
        if emission:
            m["material"]["emission"] = emission
        meshes.append(m)

    quad_mesh("floor", [(0, 0, 0), (0, 0, 2), (2, 0, 2), (2, 0, 0)], white)
    quad_mesh("ceiling", [(0, 2, 0), (2, 2, 0), (2, 2, 2), (0, 2, 2)], white)
    quad_mesh("back wall", [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0)], white)
    quad_mesh("front wall", [(0, 0, 2), (0, 2, 2), (2, 2, 2), (2, 0, 2)], white)
    quad_mesh("left wall", [(0, 0, 0), (0, 2, 0), (0, 2, 2), (0, 0, 2)], red)
    quad_mesh("right wall", [(2, 0, 0), (2, 0, 2), (2, 2, 2), (2, 2, 0)], green)
    quad_mesh("light panel", [(0.75, 1.98, 0.75), (1.25, 1.98, 0.75), (1.25, 1.98, 1.25), (0.75, 1.98, 1.25)],
              [0.0, 0.0, 0.0], [17.0, 12.0, 4.0])
    v, i = [], []
    box(v, i, (0.3, 0.0, 0.3), (0.9, 1.2, 0.9), inward=False)
    box(v, i, (1.1, 0.0, 1.1), (1.7, 0.6, 1.7), inward=False)
    write_obj("cornell_blocks.obj", v, i, "two blocks standing in the Cornell box")
    meshes.append({"name": "blocks", "file": "cornell_blocks.obj", "material": {"albedo": white}})
    probes = [p for p in grid((0.2, 0.2, 0.2), (1.8, 1.8, 1.8), (4, 4, 4))
              if not (0.3 <= p[0] <= 0.9 and p[1] <= 1.2 and 0.3 <= p[2] <= 0.9)
              and not (1.1 <= p[0] <= 1.7 and p[1] <= 0.6 and 1.1 <= p[2] <= 1.7)]
    write_json("cornell_box.json", {
        "name": "cornell box",
        "description": "a closed box lit by an emissive ceiling panel; no sky, no lights",
        "meshes": meshes,
        "probes": probes,
    })


def two_rooms():
    # Two 4 x 3 x 4 m rooms side by side along x, joined by a door in the shared wall; a window in
    # the east wall of the second room lets the sun in; a sky outside; a lamp in the first room.
    v, i = [], []
    # Floors and ceilings (one-sided, facing into the rooms).
    quad(v, i, (0, 0, 0), (0, 0, 4), (8.2, 0, 4), (8.2, 0, 0))
    quad(v, i, (0, 3, 0), (8.2, 3, 0), (8.2, 3, 4), (0, 3, 4))
    # North and south walls.
    quad(v, i, (0, 0, 0), (8.2, 0, 0), (8.2, 3, 0), (0, 3, 0))
    quad(v, i, (0, 0, 4), (0, 3, 4), (8.2, 3, 4), (8.2, 0, 4))
    # West wall (facing +x), the shared wall with a door (both faces), the east wall with a window.
    wall_with_holes(v, i, 0.0, (0, 3), (0, 4), [], True)
    door = (0.0, 2.1, 1.5, 2.5)
    wall_with_holes(v, i, 4.0, (0, 3), (0, 4), [door], False)
    wall_with_holes(v, i, 4.2, (0, 3), (0, 4), [door], True)
    # Door jambs and lintel: the inside of the 0.2 m thick shared wall.
    quad(v, i, (4.0, 0, 1.5), (4.2, 0, 1.5), (4.2, 2.1, 1.5), (4.0, 2.1, 1.5))
    quad(v, i, (4.0, 0, 2.5), (4.0, 2.1, 2.5), (4.2, 2.1, 2.5), (4.2, 0, 2.5))
    quad(v, i, (4.0, 2.1, 1.5), (4.2, 2.1, 1.5), (4.2, 2.1, 2.5), (4.0, 2.1, 2.5))
    window = (1.0, 2.4, 1.0, 3.0)
    wall_with_holes(v, i, 8.2, (0, 3), (0, 4), [window], False)
    write_obj("two_rooms.obj", v, i, "two rooms joined by a door, a window in the east wall")
    # A table in the second room, outward-facing.
    t, ti = [], []
    box(t, ti, (5.6, 0.0, 1.4), (6.8, 0.75, 2.6), inward=False)
    probes = grid((0.5, 0.5, 0.5), (3.5, 2.5, 3.5), (4, 3, 4)) + grid((4.7, 0.5, 0.5), (7.7, 2.5, 3.5), (4, 3, 4))
    probes = [p for p in probes if not (5.6 <= p[0] <= 6.8 and p[1] <= 0.75 and 1.4 <= p[2] <= 2.6)]
    probes += [[4.1, 1.0, 2.0], [4.1, 1.8, 2.0]]  # in the doorway
    sun = {"direction": [-0.8, -0.45, 0.1], "color": [1.0, 0.95, 0.85], "intensity": 6.0}
    lamp = {"position": [2.0, 2.6, 2.0], "color": [1.0, 0.8, 0.6], "intensity": 8.0, "range": 6.0}
    # The same rooms, table and lights as glTF 2.0 (no sky and no probes: glTF cannot say them); the
    # sun's intensity is lux and the lamp's candela, which the library takes one to one.
    write_gltf("two_rooms.gltf", [("rooms", v, i, (0.7, 0.68, 0.64)), ("table", t, ti, (0.45, 0.3, 0.18))],
               [("sun", {"type": "directional", "color": sun["color"], "intensity": sun["intensity"]}, None,
                 sun["direction"]),
                ("lamp", {"type": "point", "color": lamp["color"], "intensity": lamp["intensity"],
                          "range": lamp["range"]}, lamp["position"], None)],
               "two rooms joined by a door, sun through an east window, a lamp in the west room")
    write_json("two_rooms.json", {
        "name": "two rooms",
        "description": "two rooms joined by a door; low sun through an east window; a lamp in the west room",
        "meshes": [
            {"name": "rooms", "file": "two_rooms.obj", "material": {"albedo": [0.7, 0.68, 0.64]}},
            {"name": "table", "vertices": [list(p) for p in t], "indices": ti,
             "material": {"albedo": [0.45, 0.3, 0.18]}},
        ],
        "lights": [
            dict({"name": "sun", "type": "directional"}, **sun, mode="baked", shadows=True),
            dict({"name": "lamp", "type": "point"}, **lamp, mode="baked", shadows=True),
        ],
        "sky": {"color": [0.35, 0.5, 0.8]},
        "probes": probes,
    })


def race_track():
    # A 400 m x 12 m strip of asphalt with grass beside it, a grandstand and a bridge over the
    # track; low sun and a blue sky; a realtime floodlight; probes on one flat layer 1 m up.
    meshes = []
    v, i = [], []
    quad(v, i, (0, 0, -6), (0, 0, 6), (400, 0, 6), (400, 0, -6))
    meshes.append({"name": "asphalt", "vertices": [list(p) for p in v], "indices": i,
                   "material": {"albedo": [0.08, 0.08, 0.08]}})
    v, i = [], []
    quad(v, i, (-20, -0.01, -40), (-20, -0.01, -6), (420, -0.01, -6), (420, -0.01, -40))
    quad(v, i, (-20, -0.01, 6), (-20, -0.01, 40), (420, -0.01, 40), (420, -0.01, 6))
    meshes.append({"name": "grass", "vertices": [list(p) for p in v], "indices": i,
                   "material": {"albedo": [0.15, 0.35, 0.1]}})
    v, i = [], []
    box(v, i, (150, 0, 9), (210, 8, 16), inward=False)
    meshes.append({"name": "grandstand", "vertices": [list(p) for p in v], "indices": i,
                   "material": {"albedo": [0.6, 0.6, 0.62]}})
    v, i = [], []
    box(v, i, (300, 5, -10), (306, 6, 10), inward=False)
    box(v, i, (300, 0, -10), (306, 5, -8), inward=False)
    box(v, i, (300, 0, 8), (306, 5, 10), inward=False)
    meshes.append({"name": "bridge", "vertices": [list(p) for p in v], "indices": i,
                   "material": {"albedo": [0.5, 0.48, 0.45]}})
    v, i = [], []
    box(v, i, (60, 0, -30), (64, 12, -26), inward=False)
    meshes.append({"name": "tower far from the track", "vertices": [list(p) for p in v], "indices": i,
                   "material": {"albedo": [0.4, 0.4, 0.4]}})
    probes = grid((0, 1, -5), (400, 1, 5), (41, 1, 3))
    write_json("race_track.json", {
        "name": "race track",
        "description": "a long flat outdoor strip; sun, sky and a realtime floodlight; one flat layer of probes",
        "meshes": meshes,
        "lights": [
            {"name": "sun", "type": "directional", "direction": [0.3, -0.5, 0.8], "color": [1.0, 0.97, 0.9],
             "intensity": 5.0, "mode": "baked", "shadows": True},
            {"name": "floodlight", "type": "spot", "position": [180, 20, -20], "direction": [0, -1, 1],
             "color": [1.0, 1.0, 1.0], "intensity": 4000.0, "range": 80.0, "inner_angle": 40, "outer_angle": 70,
             "mode": "realtime", "shadows": True},
            {"name": "pit lane lamp", "type": "point", "position": [-100, 5, 30], "color": [1.0, 0.9, 0.7],
             "intensity": 50.0, "range": 30.0, "mode": "baked", "shadows": True},
        ],
        "sky": {"color": [0.4, 0.55, 0.9]},
        "probes": probes,
    })


if __name__ == "__main__":
    cornell_box()
    two_rooms()
    race_track()
