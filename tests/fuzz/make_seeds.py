#!/usr/bin/env python3
"""Regenerates the glTF and GLB seeds of tests/fuzz/corpus from the sample
scenes in ../shared/assets: each scene with its buffers and images embedded
(data: URIs for gltf_json, the BIN chunk and bufferViews for glb), so that
a seed loads from the fuzz target's scratch folder, which holds nothing
else. Only seeds under 64 KiB are kept. Also the environment target's .hdr
seeds (small panoramas: flat, new-style and old-style run-length, bottom-up);
its EXR seeds are `quadra env` outputs of those (rle-16x4.exr) and the image
target's checker EXR. Usage: make_seeds.py ASSETS CORPUS"""
import base64, json, os, struct, sys

LIMIT = 64 * 1024


def embedded(path):
    folder = os.path.dirname(path)
    with open(path) as f:
        doc = json.load(f)
    for item in doc.get("buffers", []) + doc.get("images", []):
        uri = item.get("uri")
        if uri is None or uri.startswith("data:"):
            continue
        with open(os.path.join(folder, uri), "rb") as f:
            data = f.read()
        kind = "application/octet-stream" if "byteLength" in item else "image/png"
        if uri.lower().endswith((".jpg", ".jpeg")):
            kind = "image/jpeg"
        item["uri"] = "data:%s;base64,%s" % (kind, base64.b64encode(data).decode())
    return doc


def glb(doc):
    # One BIN chunk: buffer 0 keeps its bytes, images become bufferViews after it.
    buffers = doc.get("buffers", [])
    if len(buffers) > 1:
        return None
    blob = b""
    if buffers:
        blob = base64.b64decode(buffers[0].pop("uri").split(",", 1)[1])
    for image in doc.get("images", []):
        if "uri" not in image:
            continue
        kind, data = image.pop("uri").split(",", 1)
        blob += b"\0" * (-len(blob) % 4)
        doc.setdefault("bufferViews", []).append(
            {"buffer": 0, "byteOffset": len(blob), "byteLength": len(base64.b64decode(data))})
        image["bufferView"] = len(doc["bufferViews"]) - 1
        image["mimeType"] = kind[5:].split(";")[0]
        blob += base64.b64decode(data)
    blob += b"\0" * (-len(blob) % 4)
    if blob:
        doc["buffers"] = [{"byteLength": len(blob)}]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    if blob:
        chunks += struct.pack("<II", len(blob), 0x004E4942) + blob
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def hdr_header(width, height, orientation=None):
    resolution = orientation or "-Y %d +X %d" % (height, width)
    return b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1.0\n\n" + resolution.encode() + b"\n"


def hdr_texels(width, height):
    # A gradient with stretches of equal texels, so every encoding has runs.
    return [bytes([(16 * x) % 256, (32 * y) % 256, 128 if x < width // 2 else 7, 128 + (x // 4) % 3])
            for y in range(height) for x in range(width)]


def hdr_rle(width, height, texels):
    out = b""
    for y in range(height):
        out += bytes([2, 2, width >> 8, width & 255])
        for c in range(4):
            row = [texels[y * width + x][c] for x in range(width)]
            x = 0
            while x < width:
                run = 1
                while x + run < width and row[x + run] == row[x] and run < 127:
                    run += 1
                if run >= 3:
                    out += bytes([128 + run, row[x]])
                else:
                    out += bytes([run] + row[x:x + run])
                x += run
    return out


def hdr_old_rle(width, height, texels):
    out = b""
    for y in range(height):
        x = 0
        while x < width:
            t = texels[y * width + x]
            out += t
            repeats = 0
            while x + 1 + repeats < width and texels[y * width + x + 1 + repeats] == t:
                repeats += 1
            if repeats:
                out += bytes([1, 1, 1, repeats])
            x += 1 + repeats
    return out


def environment_seeds(corpus):
    folder = os.path.join(corpus, "environment")
    os.makedirs(folder, exist_ok=True)
    seeds = {
        "flat-4x2.hdr": hdr_header(4, 2) + b"".join(hdr_texels(4, 2)),
        "bottom-up-4x2.hdr": hdr_header(4, 2, "+Y 2 -X 4") + b"".join(hdr_texels(4, 2)),
        "rle-16x4.hdr": hdr_header(16, 4) + hdr_rle(16, 4, hdr_texels(16, 4)),
        "old-rle-12x2.hdr": hdr_header(12, 2) + hdr_old_rle(12, 2, hdr_texels(12, 2)),
    }
    for name, data in seeds.items():
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data)


def main(assets, corpus):
    environment_seeds(corpus)
    for name in sorted(os.listdir(assets)):
        path = os.path.join(assets, name, "glTF", name + ".gltf")
        if not os.path.exists(path):
            continue
        try:
            doc = embedded(path)
        except OSError:
            continue
        text = json.dumps(doc, separators=(",", ":")).encode()
        if len(text) < LIMIT:
            with open(os.path.join(corpus, "gltf_json", name + ".gltf"), "wb") as f:
                f.write(text)
        binary = glb(doc)
        if binary and len(binary) < LIMIT:
            with open(os.path.join(corpus, "glb", name + ".glb"), "wb") as f:
                f.write(binary)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
