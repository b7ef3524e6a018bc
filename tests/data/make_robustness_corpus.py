#!/usr/bin/env python3
"""Writes the robustness corpus (tests/data/robustness/): small, valid-but-unusual and broken model
files of every kind Tandem loads. The files are committed; rerun this script (standard library
only; the Draco file also needs Debian's `draco` package) after changing it. Each file's expected
outcome is listed in EXPECTED.tsv, which robustness_corpus_test.cpp checks: `render` (exit 0 with a
finite, non-black image) or `error` (exit 2, a message naming the file and the fragment given)."""
import base64, json, math, os, struct, subprocess, sys, tempfile, zlib

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "robustness")
expected = []


def write(name, data, outcome, fragment=""):
    path = os.path.join(OUT, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    if outcome:
        expected.append((name, outcome, fragment))


def png(w, h, rgb):
    """A tiny RGB PNG: rgb(x, y) -> (r, g, b) bytes."""
    raw = b"".join(b"\0" + bytes(c for x in range(w) for c in rgb(x, y)) for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def data_uri(b, mime="application/octet-stream"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(b).decode())


def gltf(buffers, views, accessors, primitives, extra=None, materials=None):
    doc = {"asset": {"version": "2.0"},
           "buffers": [{"byteLength": len(b), "uri": data_uri(b)} for b in buffers],
           "bufferViews": views, "accessors": accessors,
           "meshes": [{"primitives": primitives}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],
           "scene": 0}
    if materials:
        doc["materials"] = materials
    doc.update(extra or {})
    return json.dumps(doc, indent=1)


def f32(*v):
    return struct.pack("<%df" % len(v), *v)


def positions_accessor(view, count, lo, hi, **kw):
    a = {"bufferView": view, "componentType": 5126, "count": count, "type": "VEC3", "min": lo, "max": hi}
    a.update(kw)
    return a


def make_gltf():
    # A unit quad as a triangle strip, and a hexagon as a fan (modes 5 and 6).
    quad = f32(0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0)
    write("strip.gltf", gltf([quad], [{"buffer": 0, "byteLength": len(quad)}],
                             [positions_accessor(0, 4, [0, 0, 0], [1, 1, 0])],
                             [{"attributes": {"POSITION": 0}, "mode": 5}]), "render")
    hexa = [0.0, 0.0, 0.0]
    for k in range(7):
        a = 2 * math.pi * k / 6
        hexa += [math.cos(a), math.sin(a), 0.0]
    hb = f32(*hexa)
    write("fan.gltf", gltf([hb], [{"buffer": 0, "byteLength": len(hb)}],
                           [positions_accessor(0, 8, [-1, -1, 0], [1, 1, 0])],
                           [{"attributes": {"POSITION": 0}, "mode": 6}]), "render")
    # Sparse: a flat quad whose vertex 3 is lifted by a sparse substitution, and a sparse accessor
    # without a bufferView (zeros, then two vertices substituted).
    idx = struct.pack("<4H", 0, 1, 2, 3) + struct.pack("<6H", 0, 1, 2, 2, 1, 3)
    sp_idx = struct.pack("<I", 3)
    sp_val = f32(1, 1, 0.5)
    b = quad + idx + sp_idx + sp_val
    views = [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 56, "byteLength": 12},
             {"buffer": 0, "byteOffset": 68, "byteLength": 4}, {"buffer": 0, "byteOffset": 72, "byteLength": 12}]
    acc = [positions_accessor(0, 4, [0, 0, 0], [1, 1, 0.5],
                              sparse={"count": 1, "indices": {"bufferView": 2, "componentType": 5125},
                                      "values": {"bufferView": 3}}),
           {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    write("sparse.gltf", gltf([b], views, acc, [{"attributes": {"POSITION": 0}, "indices": 1}]), "render")
    zb = struct.pack("<2B", 1, 2) + b"\0\0" + f32(1, 0, 0, 0, 1, 0)
    acc = [{"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
            "sparse": {"count": 2, "indices": {"bufferView": 0, "componentType": 5121},
                       "values": {"bufferView": 1}}}]
    write("sparse_no_bufferview.gltf",
          gltf([zb], [{"buffer": 0, "byteLength": 2}, {"buffer": 0, "byteOffset": 4, "byteLength": 24}],
               acc, [{"attributes": {"POSITION": 0}}]), "render")
    # Points and lines beside triangles are skipped; points alone are an error.
    tri = f32(0, 0, 0, 1, 0, 0, 0, 1, 0)
    one = gltf([tri], [{"buffer": 0, "byteLength": 36}], [positions_accessor(0, 3, [0, 0, 0], [1, 1, 0])],
               [{"attributes": {"POSITION": 0}, "mode": 0}])
    write("points_only.gltf", one, "error", "point or line primitives skipped")
    write("lines_and_triangles.gltf",
          gltf([tri], [{"buffer": 0, "byteLength": 36}], [positions_accessor(0, 3, [0, 0, 0], [1, 1, 0])],
               [{"attributes": {"POSITION": 0}, "mode": 1}, {"attributes": {"POSITION": 0}}]), "render")
    # Lying lengths: a buffer shorter than its byteLength says, an accessor counting past its view.
    doc = json.loads(gltf([tri], [{"buffer": 0, "byteLength": 36}],
                          [positions_accessor(0, 3, [0, 0, 0], [1, 1, 0])], [{"attributes": {"POSITION": 0}}]))
    doc["buffers"][0]["byteLength"] = 3600
    write("lying_buffer_length.gltf", json.dumps(doc), "error", "")
    doc = json.loads(gltf([tri], [{"buffer": 0, "byteLength": 36}],
                          [positions_accessor(0, 30, [0, 0, 0], [1, 1, 0])], [{"attributes": {"POSITION": 0}}]))
    write("lying_accessor_count.gltf", json.dumps(doc), "error", "")
    # glTF 1.0, as JSON and as binary (KHR_binary_glTF header version 1).
    write("gltf1.gltf", json.dumps({"asset": {"version": "1.0"}, "meshes": {"m": {"primitives": []}},
                                    "scene": "s", "scenes": {"s": {"nodes": []}}}), "error", "glTF 1.0")
    write("gltf1_no_asset.gltf", json.dumps({"meshes": {"m": {"primitives": []}}, "nodes": {}}),
          "error", "glTF 1.0")
    body = b'{"scene":"s"}   '
    write("gltf1.glb", b"glTF" + struct.pack("<III", 1, 20 + len(body), len(body)) + struct.pack("<I", 0) + body,
          "error", "glTF 1.0")
    # A UTF-8 byte order mark before the JSON.
    write("utf8_bom.gltf", b"\xef\xbb\xbf" + gltf([tri], [{"buffer": 0, "byteLength": 36}],
                                                    [positions_accessor(0, 3, [0, 0, 0], [1, 1, 0])],
                                                    [{"attributes": {"POSITION": 0}}]).encode(), "render")
    # Occlusion: a checker in R darkens the ambient term (the model is lit only by ambient).
    checker = png(8, 8, lambda x, y: (255, 255, 255) if (x + y) % 2 else (40, 40, 40))
    uv = f32(0, 1, 1, 1, 0, 0, 1, 0)
    b = quad + uv + struct.pack("<6H", 0, 1, 2, 2, 1, 3)
    doc = json.loads(gltf([b], [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                                {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
                          [positions_accessor(0, 4, [0, 0, 0], [1, 1, 0]),
                           {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                           {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
                          [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}],
                          materials=[{"occlusionTexture": {"index": 0, "strength": 1.0},
                                      "pbrMetallicRoughness": {"metallicFactor": 0.0}}]))
    doc["images"] = [{"uri": data_uri(checker, "image/png")}]
    doc["textures"] = [{"source": 0}]
    write("occlusion.gltf", json.dumps(doc), "render")
    # Empty files.
    write("empty.gltf", b"", "error", "")
    write("empty.glb", b"", "error", "")
    write("not_json.gltf", "{ this is not json", "error", "")


def make_draco():
    drc_src = os.path.join(OUT, ".cube.drc.src")
    cube = "".join(["v %d %d %d\n" % (x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)])
    cube += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    cube += "vn 0 0 -1\nvn 0 0 1\nvn -1 0 0\nvn 1 0 0\nvn 0 -1 0\nvn 0 1 0\n"
    faces = [(1, 3, 4, 2, 1), (5, 6, 8, 7, 2), (1, 5, 7, 3, 3), (2, 4, 8, 6, 4), (1, 2, 6, 5, 5), (3, 7, 8, 4, 6)]
    for a, b, c, d, n in faces:
        cube += "f %d/1/%d %d/2/%d %d/3/%d %d/4/%d\n" % (a, n, b, n, c, n, d, n)
    write("draco_cube_source.obj", cube, "render")
    try:
        with tempfile.TemporaryDirectory() as t:
            src = os.path.join(t, "cube.obj")
            open(src, "w").write(cube)
            subprocess.run(["draco_encoder", "-i", src, "-o", drc_src, "-qp", "0", "-qt", "0", "-qn", "0"],
                           check=True, capture_output=True)
    except (OSError, subprocess.CalledProcessError):
        if not os.path.exists(drc_src):
            sys.exit("draco_encoder (Debian package draco) is needed once to make the Draco stream")
    drc = open(drc_src, "rb").read()
    # draco_encoder's OBJ attribute ids: POSITION 0, TEXCOORD 1, NORMAL 2.
    def doc(ids):
        d = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_draco_mesh_compression"],
             "extensionsRequired": ["KHR_draco_mesh_compression"],
             "buffers": [{"byteLength": len(drc), "uri": data_uri(drc)}],
             "bufferViews": [{"buffer": 0, "byteLength": len(drc)}],
             "accessors": [{"componentType": 5126, "count": 24, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
                           {"componentType": 5126, "count": 24, "type": "VEC3"},
                           {"componentType": 5126, "count": 24, "type": "VEC2"},
                           {"componentType": 5125, "count": 36, "type": "SCALAR"}],
             "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                         "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0,
                                                                                       "attributes": ids}}}]}],
             "nodes": [{"mesh": 0, "rotation": [0.2, 0.3, 0.0, 0.93]}], "scenes": [{"nodes": [0]}], "scene": 0}
        return json.dumps(d, indent=1)
    write("draco_cube.gltf", doc({"POSITION": 0, "TEXCOORD_0": 1, "NORMAL": 2}), "render")
    # The same as binary glTF: JSON chunk, then the Draco stream in the BIN chunk.
    d = json.loads(doc({"POSITION": 0, "TEXCOORD_0": 1, "NORMAL": 2}))
    del d["buffers"][0]["uri"]
    j = json.dumps(d).encode()
    j += b" " * ((4 - len(j) % 4) % 4)
    b = drc + b"\0" * ((4 - len(drc) % 4) % 4)
    write("draco_cube.glb", b"glTF" + struct.pack("<II", 2, 12 + 8 + len(j) + 8 + len(b)) +
          struct.pack("<I", len(j)) + b"JSON" + j + struct.pack("<I", len(b)) + b"BIN\0" + b, "render")
    # A BIN chunk claiming 4 bytes more than the file holds (tinygltf 2.7 reads past the end:
    # found by fuzz_glb); the header's total length is the true one.
    glb = (b"glTF" + struct.pack("<II", 2, 12 + 8 + len(j) + 8 + len(b)) + struct.pack("<I", len(j)) + b"JSON" + j +
           struct.pack("<I", len(b) + 4) + b"BIN\0" + b)
    write("glb_bin_chunk_overrun.glb", glb, "error", "BIN chunk length exceeds the file")
    write("draco_wrong_attribute_id.gltf", doc({"POSITION": 0, "TEXCOORD_0": 1, "NORMAL": 7}), "error",
          "Draco attribute id 7")
    d = json.loads(doc({"POSITION": 0, "TEXCOORD_0": 1, "NORMAL": 2}))
    d["buffers"][0]["uri"] = data_uri(drc[: len(drc) // 2])
    d["buffers"][0]["byteLength"] = d["bufferViews"][0]["byteLength"] = len(drc) // 2
    write("draco_truncated.gltf", json.dumps(d), "error", "Draco")


def make_obj():
    tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    # A 5000-vertex convex polygon (a fan) and a 3000-vertex star (not convex: ear clipping).
    def polygon(n, wave):
        verts = "".join("v %.6f %.6f 0\n" % ((1 + wave * (k % 2)) * math.cos(2 * math.pi * k / n),
                                               (1 + wave * (k % 2)) * math.sin(2 * math.pi * k / n))
                        for k in range(n))
        return verts + "f " + " ".join(str(k + 1) for k in range(n)) + "\n"
    write("huge_polygon.obj", polygon(5000, 0.0), "render")
    write("star_polygon.obj", polygon(3000, 0.3), "render")
    write("utf8_bom.obj", b"\xef\xbb\xbf" + tri.encode(), "render")
    write("utf16le_bom.obj", b"\xff\xfe" + tri.encode("utf-16-le"), "render")
    write("utf16be_bom.obj", b"\xfe\xff" + tri.encode("utf-16-be"), "render")
    write("crlf.obj", tri.replace("\n", "\r\n"), "render")
    write("windows_paths.obj", "mtllib windows_paths.mtl\nusemtl wood\n" +
          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n", "render")
    write("windows_paths.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd .\\textures\\checker.png\n", None)
    write("textures/checker.png", png(8, 8, lambda x, y: (200, 120, 40) if (x + y) % 2 else (60, 30, 10)), None)
    write("glass_tf_illum7.obj", "mtllib glass.mtl\nusemtl glass\n" + tri, "render")
    write("glass.mtl", "newmtl glass\nKd 0.1 0.1 0.1\nKs 1 1 1\nNi 1.5\nTf 0.6 1 0.7\nillum 7\n", None)
    write("missing_mtl.obj", "mtllib nowhere.mtl\nusemtl x\n" + tri, "render")
    # mtllib naming a folder, in a file Tandem rewrites (a byte-order mark): read as no library
    # (reading the folder threw from inside libstdc++: found by fuzz_obj).
    write("mtllib_names_a_folder.obj", b"\xef\xbb\xbf" + ("mtllib textures\nusemtl x\n" + tri).encode(), "render")
    write("empty.obj", b"", "error", "")
    write("vertices_only.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "error", "no triangles")
    write("index_out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "error", "")
    write("nan_vertex.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "error", "")
    write("binary_garbage.obj", bytes(range(256)) * 4, "error", "")


def make_scene_files():
    write("empty.json", b"", "error", "")
    write("truncated.json", '{"objects": [{"type": "cube"', "error", "")
    write("unknown_model.json", json.dumps({"objects": [{"file": "does_not_exist.obj"}]}), "error",
          "does_not_exist.obj")


def main():
    make_gltf()
    make_draco()
    make_obj()
    make_scene_files()
    with open(os.path.join(OUT, "EXPECTED.tsv"), "w") as f:
        f.write("# file\texpected (render: exit 0, finite non-black image; error: exit 2 naming the file)\tmessage fragment\n")
        for name, outcome, fragment in sorted(expected):
            f.write("%s\t%s\t%s\n" % (name, outcome, fragment))
    print("wrote %d corpus files to %s" % (len(expected), OUT))


if __name__ == "__main__":
    main()
