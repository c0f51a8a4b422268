#!/usr/bin/env python3
"""Assembles the fuzz seed corpora at run time (nothing here is copied into the repository).

  OUT/fuzz_gltf/seeds        the shared test scenes' .gltf/.glb files (../shared/scenes, up to
                             MAX_SEED_BYTES each) and a few tiny glTF files written here, which reach
                             the parts the big scenes do not (data URIs, external buffers and images,
                             textures, lights, cameras, TRS nodes, extensions)
  OUT/fuzz_scene_file/seeds  the repository's scenes/*.json, plus a scene file with a "gltf:" source;
                             "gltf:" sources are rewritten to the file's name, the file goes in OUT/files
  OUT/files                  side files the seeds refer to: the harness copies them into its sandbox

Usage: make_corpus.py --shared DIR --repo DIR --out DIR
Without the shared scenes it writes the generated seeds only, with a warning; with CI=true it fails.
"""

import argparse
import base64
import json
import os
import shutil
import struct
import sys
import zlib

# Bigger files make every execution slower (the corpus files are parsed whole); the shared scenes
# above this (dabrovic-sponza.glb, 3.3 MB of textures) add little that the small ones do not.
MAX_SEED_BYTES = 256 * 1024


def png_rgba(width, height, pixels):
    """A minimal RGBA8 PNG (pixels: bytes, row-major, 4 per pixel)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\x00" + pixels[y * width * 4:(y + 1) * width * 4] for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def triangle_gltf(buffer_uri, image_uri):
    """One textured, lit triangle: (glTF JSON dict, binary buffer bytes)."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    normals = struct.pack("<9f", 0, 0, 1, 0, 0, 1, 0, 0, 1)
    uvs = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    indices = struct.pack("<3H", 0, 1, 2) + b"\x00\x00"  # padded to 4 bytes
    data = positions + normals + uvs + indices
    views = [(0, 36, 34962), (36, 36, 34962), (72, 24, 34962), (96, 6, 34963)]
    doc = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [
            {"mesh": 0, "translation": [0, 0, -1], "rotation": [0, 0, 0, 1], "scale": [2, 2, 2], "children": [4]},
            {"camera": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0.5, 3, 1]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 1, 1]},
            {"extensions": {"KHR_lights_punctual": {"light": 1}}, "rotation": [-0.3826834, 0, 0, 0.9238795]},
            {"mesh": 0, "name": "child", "translation": [1, 0, 0]},
        ],
        "meshes": [{"name": "triangle", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0, "mode": 4}]}],
        "materials": [{
            "name": "textured",
            "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1], "baseColorTexture": {"index": 0},
                                     "metallicFactor": 0.1, "roughnessFactor": 0.7},
            "emissiveFactor": [0.1, 0.1, 0.1], "doubleSided": True,
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2},
                           "KHR_materials_specular": {"specularFactor": 0.5}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 33071}],
        "images": [{"uri": image_uri}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100, "aspectRatio": 1.5}}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.9, 0.8], "intensity": 5, "range": 10},
            {"type": "spot", "intensity": 3, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}}]}},
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": n, "target": t} for o, n, t in views],
        "buffers": [{"byteLength": len(data)} | ({"uri": buffer_uri} if buffer_uri is not None else {})],
    }
    return doc, data


def glb(doc, data):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\x00" * (-len(data) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(data), b"BIN\x00") + data
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def write(path, content):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(content if isinstance(content, bytes) else content.encode())


def external_uris(path):
    """The relative, non-data URIs of a .gltf file's buffers and images (they must travel with it)."""
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return []
    uris = [item.get("uri", "") for key in ("buffers", "images") for item in doc.get(key, []) if isinstance(item, dict)]
    return [u for u in uris if u and not u.startswith("data:") and "://" not in u and not os.path.isabs(u)]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--shared", required=True)
    parser.add_argument("--repo", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()

    shutil.rmtree(args.out, ignore_errors=True)
    gltf_seeds = os.path.join(args.out, "fuzz_gltf", "seeds")
    scene_seeds = os.path.join(args.out, "fuzz_scene_file", "seeds")
    files = os.path.join(args.out, "files")
    for d in (gltf_seeds, scene_seeds, files):
        os.makedirs(d)

    # Generated seeds: embedded (data URIs), external files, binary.
    texture = png_rgba(2, 2, bytes([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128]))
    data_uri = "data:application/octet-stream;base64,"
    doc, data = triangle_gltf(data_uri + base64.b64encode(triangle_gltf(None, "")[1]).decode(),
                              "data:image/png;base64," + base64.b64encode(texture).decode())
    write(os.path.join(gltf_seeds, "triangle-embedded.gltf"), json.dumps(doc, indent=1))
    doc, data = triangle_gltf("triangle.bin", "texture.png")
    write(os.path.join(gltf_seeds, "triangle-external.gltf"), json.dumps(doc, indent=1))
    write(os.path.join(files, "triangle-external.gltf"), json.dumps(doc, indent=1))
    write(os.path.join(files, "triangle.bin"), data)
    write(os.path.join(files, "texture.png"), texture)
    doc, data = triangle_gltf(None, "texture.png")
    write(os.path.join(gltf_seeds, "triangle.glb"), glb(doc, data))
    write(os.path.join(files, "triangle.glb"), glb(doc, data))

    # The shared test scenes.
    scenes = os.path.join(args.shared, "scenes")
    found = 0
    if os.path.isdir(scenes):
        for root, _, names in sorted(os.walk(scenes)):
            for name in sorted(names):
                path = os.path.join(root, name)
                if not name.lower().endswith((".gltf", ".glb")):
                    continue
                if os.path.getsize(path) > MAX_SEED_BYTES:
                    print(f"make_corpus: skipped {path} ({os.path.getsize(path)} bytes > {MAX_SEED_BYTES})")
                    continue
                shutil.copyfile(path, os.path.join(gltf_seeds, name))
                for uri in external_uris(path) if name.lower().endswith(".gltf") else []:
                    source = os.path.normpath(os.path.join(root, uri))
                    if os.path.isfile(source) and not uri.startswith(".."):
                        write(os.path.join(files, uri), open(source, "rb").read())
                found += 1
    if found == 0:
        message = f"make_corpus: no glTF scenes under {scenes}: only the generated seeds"
        if os.environ.get("CI") == "true":
            print(message + " (CI=true: failing)", file=sys.stderr)
            return 1
        print("WARNING: " + message, file=sys.stderr)

    # Scene files: the repository's, with "gltf:" sources pointing into the sandbox.
    scene_dir = os.path.join(args.repo, "scenes")
    for name in sorted(os.listdir(scene_dir)):
        if not name.endswith(".json"):
            continue
        path = os.path.join(scene_dir, name)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        try:
            doc = json.loads(text)
            source = doc.get("source", "") if isinstance(doc, dict) else ""
        except ValueError:
            source = ""
        if isinstance(source, str) and source.startswith("gltf:"):
            gltf = os.path.normpath(os.path.join(scene_dir, source[5:]))
            if os.path.isfile(gltf) and os.path.getsize(gltf) <= MAX_SEED_BYTES:
                shutil.copyfile(gltf, os.path.join(files, os.path.basename(gltf)))
                doc["source"] = "gltf:" + os.path.basename(gltf)
                text = json.dumps(doc, indent=1)
        write(os.path.join(scene_seeds, name), text)
    write(os.path.join(scene_seeds, "gltf-source.json"), json.dumps({
        "name": "fuzz", "source": "gltf:triangle-external.gltf", "technique": "smcir", "replaceLights": False,
        "lights": [{"name": "key", "type": "spot", "position": [0, 2, 2], "direction": [0, -1, -1],
                    "color": [1, 1, 1], "intensity": 10, "innerConeDeg": 20, "outerConeDeg": 40, "range": 0}],
        "replaceCameras": True,
        "cameras": [{"name": "default", "position": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0],
                     "fovYDeg": 45, "zNear": 0.1, "zFar": 50}],
        "animations": [{"name": "orbit", "camera": "default",
                        "keys": [{"t": 0, "position": [0, 0, 3], "target": [0, 0, 0]},
                                 {"t": 1, "position": [3, 0, 0], "target": [0, 0, 0]}]},
                       {"name": "sweep", "light": "key",
                        "keys": [{"t": 0, "position": [0, 2, 2], "target": [0, 0, 0]}]}],
        "settings": {"renderer.exposure": 2, "smcir.vplCount": 256, "renderer.toneMap": "aces", "x.flag": True},
    }, indent=1))
    write(os.path.join(scene_seeds, "glb-source.json"),
          json.dumps({"source": "gltf:triangle.glb", "lights": [{"name": "sun", "type": "directional",
                                                                   "direction": [0, -1, 0], "intensity": 2}]}))

    counts = {h: len(os.listdir(os.path.join(args.out, h, "seeds"))) for h in ("fuzz_gltf", "fuzz_scene_file")}
    print(f"make_corpus: {counts['fuzz_gltf']} glTF seeds ({found} shared scenes), {counts['fuzz_scene_file']} "
          f"scene-file seeds, {len(os.listdir(files))} side files in {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
