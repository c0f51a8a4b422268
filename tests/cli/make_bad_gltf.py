#!/usr/bin/env python3
"""Writes the glTF (and scene-file) inputs of tests/cli/bad_input.sh into DIR, one file per case.

Every file is a tiny variation of one good scene (a 2 m floor quad facing +y and a point light
above it), broken in exactly one way, so that each case tests one thing. Written at test time
(stdlib only) rather than checked in: the bytes that matter (NaNs, strides, offsets) are visible
here next to what they test.

usage: make_bad_gltf.py DIR
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125

# The floor quad: 4 vertices, 2 triangles, normals +y.
QUAD_POSITIONS = [-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1]
QUAD_NORMALS = [0, 1, 0] * 4
QUAD_INDICES = [0, 2, 1, 0, 3, 2]


class Gltf:
    """One glTF document with one binary buffer (a data URI, a .bin file or a .glb chunk)."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0"}}
        self.bin = b""

    def append(self, array, value):
        self.doc.setdefault(array, []).append(value)
        return len(self.doc[array]) - 1

    def view(self, data, stride=0):
        self.bin += b"\0" * (-len(self.bin) % 4)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        self.bin += data
        return self.append("bufferViews", view)

    def accessor(self, values, fmt, component_type, type_name, components, **extra):
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        accessor = {"bufferView": self.view(data), "componentType": component_type,
                    "count": len(values) // components, "type": type_name}
        accessor.update(extra)
        return self.append("accessors", accessor)

    def floats(self, values, type_name="VEC3", components=3):
        return self.accessor(values, "f", FLOAT, type_name, components)

    def mesh(self, positions, normals=None, indices=None, material=None, name="floor"):
        attributes = {"POSITION": self.floats(positions)}
        # POSITION's bounds, which glTF requires (the Khronos validator checks them: scripts/gltf-validate).
        finite = [[v for v in positions[c::3] if math.isfinite(v)] for c in range(3)]
        if all(finite):
            self.doc["accessors"][attributes["POSITION"]].update(min=[min(f) for f in finite], max=[max(f) for f in finite])
        if normals is not None:
            attributes["NORMAL"] = self.floats(normals)
        primitive = {"attributes": attributes}
        if indices is not None:
            primitive["indices"] = self.accessor(indices, "H", USHORT, "SCALAR", 1)
        if material is not None:
            primitive["material"] = material
        mesh = self.append("meshes", {"name": name, "primitives": [primitive]})
        return self.append("nodes", {"mesh": mesh, "name": name})

    def light(self, intensity=5.0, color=(1, 1, 1)):
        self.doc.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})["lights"]
        lights.append({"type": "point", "intensity": intensity, "color": list(color), "name": "lamp"})
        return self.append("nodes", {"name": "lamp", "translation": [0, 1, 0],
                                     "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})

    def finish(self, roots=None):
        self.doc["scenes"] = [{"nodes": roots if roots is not None else list(range(len(self.doc["nodes"])))}]
        self.doc["scene"] = 0

    def gltf_text(self, buffer_uri=None):
        doc = json.loads(json.dumps(self.doc))
        if self.bin:
            uri = buffer_uri or "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()
            doc["buffers"] = [{"byteLength": len(self.bin), "uri": uri}]
        return json.dumps(doc, indent=1)

    def glb_bytes(self):
        doc = json.loads(json.dumps(self.doc))
        doc["buffers"] = [{"byteLength": len(self.bin)}]
        text = json.dumps(doc).encode()
        text += b" " * (-len(text) % 4)
        binary = self.bin + b"\0" * (-len(self.bin) % 4)
        total = 12 + 8 + len(text) + 8 + len(binary)
        return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text +
                struct.pack("<II", len(binary), 0x004E4942) + binary)


def good(positions=QUAD_POSITIONS, normals=QUAD_NORMALS, indices=QUAD_INDICES, light=True):
    g = Gltf()
    g.mesh(positions, normals, indices)
    if light:
        g.light()
    g.finish()
    return g


def png(width, height, rows):
    """An 8-bit RGB PNG; `rows` is the raw scanline data (filter bytes included)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def main():
    out = sys.argv[1]
    os.makedirs(os.path.join(out, "scene"), exist_ok=True)

    def write(name, data):
        with open(os.path.join(out, name), "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode())

    nan, inf = float("nan"), float("inf")

    # The good scene, so that every bad file below differs from a loadable one in one place.
    write("good.gltf", good().gltf_text())
    write("good.glb", good().glb_bytes())

    # Empty and cut-short files.
    write("empty.gltf", b"")
    write("empty.glb", b"")
    glb = good().glb_bytes()
    write("truncated.glb", glb[: len(glb) - 40])  # the BIN chunk is cut short
    write("truncated-header.glb", glb[:10])
    write("malformed.gltf", good().gltf_text()[:-30])

    # Accessors, buffer views and strides pointing past their data.
    g = good()
    g.doc["accessors"][0]["byteOffset"] = 4096
    write("accessor-offset.gltf", g.gltf_text())
    g = good()
    g.doc["bufferViews"][0]["byteOffset"] = 1 << 20
    write("view-offset.gltf", g.gltf_text())
    g = good()
    g.doc["bufferViews"][0]["byteStride"] = 252  # 4 vertices * 252 bytes > the 48-byte view
    write("stride-past-end.gltf", g.gltf_text())
    g = good()
    g.doc["bufferViews"][0]["byteStride"] = 4  # smaller than one VEC3 float element (12 bytes)
    write("stride-small.gltf", g.gltf_text())
    g = good(indices=[0, 2, 1, 0, 3, 9])
    write("index-range.gltf", g.gltf_text())
    g = good()
    g.doc["accessors"][2]["count"] = 1 << 30  # the index accessor claims a billion indices
    write("index-count.gltf", g.gltf_text())

    # Component types: float indices, a scalar POSITION, a componentType glTF does not define.
    g = Gltf()
    positions = g.floats(QUAD_POSITIONS)
    indices = g.accessor([float(i) for i in QUAD_INDICES], "f", FLOAT, "SCALAR", 1)
    mesh = g.append("meshes", {"primitives": [{"attributes": {"POSITION": positions}, "indices": indices}]})
    g.append("nodes", {"mesh": mesh})
    g.light()
    g.finish()
    write("indices-float.gltf", g.gltf_text())
    g = good()
    g.doc["accessors"][0]["type"] = "SCALAR"
    g.doc["accessors"][0]["count"] = 12
    write("position-scalar.gltf", g.gltf_text())
    g = good()
    g.doc["accessors"][0]["componentType"] = 5130  # GL_DOUBLE: not a glTF component type
    write("component-double.gltf", g.gltf_text())

    # Non-finite vertex data.
    write("position-nan.gltf", good(positions=[nan] + QUAD_POSITIONS[1:]).gltf_text())
    write("position-inf.glb", good(positions=QUAD_POSITIONS[:4] + [inf] + QUAD_POSITIONS[5:]).glb_bytes())
    write("normal-nan.gltf", good(normals=QUAD_NORMALS[:6] + [nan] + QUAD_NORMALS[7:]).gltf_text())

    # Degenerate triangles next to good ones: dropped with a warning, the rest renders.
    # Triangle 3 repeats an index, triangle 4 has three collinear vertices (zero area).
    positions = QUAD_POSITIONS + [0, 0, 0, 0.5, 0, 0, 1, 0, 0]
    normals = QUAD_NORMALS + [0, 1, 0] * 3
    write("degenerate.gltf", good(positions=positions, normals=normals,
                                  indices=QUAD_INDICES + [0, 0, 1, 4, 5, 6]).gltf_text())
    # Nothing but degenerate triangles: no geometry is left.
    write("all-degenerate.gltf", good(indices=[0, 0, 1, 2, 2, 3]).gltf_text())
    # A zero-area emissive triangle (an "area light" that is a line): dropped like any degenerate
    # triangle, so no light source with zero area (infinite sampling density) reaches the renderer.
    g = good()
    material = g.append("materials", {"name": "lamp-line", "emissiveFactor": [1, 1, 1],
                                      "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 100}}})
    g.doc.setdefault("extensionsUsed", []).append("KHR_materials_emissive_strength")
    node = g.mesh([0, 0.5, 0, 0.5, 0.5, 0, 1, 0.5, 0], [0, -1, 0] * 3, None, material, name="lamp-line")
    g.doc["scenes"][0]["nodes"].append(node)
    write("emissive-zero-area.gltf", g.gltf_text())

    # Lights.
    write("no-lights.gltf", good(light=False).gltf_text())
    g = good()
    g.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -2
    write("light-negative.gltf", g.gltf_text())
    # JSON has no NaN: 1e999 is the way a file says "not a finite number" (parsers give inf).
    write("light-inf.gltf", good().gltf_text().replace('"intensity": 5.0', '"intensity": 1e999'))

    # External files: a texture outside the scene's folder (it exists, so only the rule refuses it),
    # an absolute texture path, a buffer outside the folder, a buffer that is missing.
    texture = png(2, 2, b"\0" + b"\xff\0\0" * 2 + b"\0" + b"\0\xff\0" * 2)
    write("outside.png", texture)
    write("outside.bin", good().bin)

    def textured(uri):
        g = good()
        g.append("images", {"uri": uri})
        g.append("textures", {"source": 0})
        g.append("materials", {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})
        g.doc["meshes"][0]["primitives"][0]["material"] = 0
        return g

    write("scene/texture-outside.gltf", textured("../outside.png").gltf_text())
    write("scene/texture-escaped.gltf", textured("sub/%2E%2E/%2e%2e/outside.png").gltf_text())
    write("scene/texture-absolute.gltf", textured(os.path.abspath(os.path.join(out, "outside.png"))).gltf_text())
    write("scene/buffer-outside.gltf", good().gltf_text(buffer_uri="../outside.bin"))
    write("scene/buffer-missing.gltf", good().gltf_text(buffer_uri="absent.bin"))

    # An image whose header claims 65536 x 32768 = 2^31 pixels (8 GiB as RGBA); the data is tiny.
    write("scene/huge.png", png(65536, 32768, b"\0" * 16))
    write("scene/texture-huge.gltf", textured("huge.png").gltf_text())

    # Unsupported required extension.
    g = good()
    g.doc["extensionsUsed"] = ["KHR_draco_mesh_compression"]
    g.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    write("required-extension.gltf", g.gltf_text())

    # Scene files.
    write("empty.json", b"")
    write("source-missing.json", json.dumps({"source": "gltf:absent.gltf"}))
    write("light-nan.json", '{"source": "builtin:cornell", "lights": [{"name": "x", "type": "point", '
                            '"position": [0, 1, 0], "intensity": 1e999}]}')
    write("animation-missing-light.json", json.dumps(
        {"source": "builtin:cornell",
         "animations": [{"name": "swing", "light": "nosuchlight", "keys": [{"t": 0, "position": [0, 1, 0]}]}]}))
    write("no-lights.json", json.dumps({"source": "gltf:no-lights.gltf"}))


if __name__ == "__main__":
    main()
