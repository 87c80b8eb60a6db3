#!/usr/bin/env python3
"""Regenerates the glTF and GLB seeds of tests/fuzz/corpus from the sample
scenes in ../shared/assets: each scene with its buffers and images embedded
(data: URIs for gltf_json, the BIN chunk and bufferViews for glb), so that
a seed loads from the fuzz target's scratch folder, which holds nothing
else. Only seeds under 64 KiB are kept. Usage: make_seeds.py ASSETS CORPUS"""
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


def main(assets, corpus):
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
