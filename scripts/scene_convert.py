"""The conversions scripts/get-scenes applies to downloaded archive members, by the name a file's
`convert` field gives in assets/scenes.json. Each takes the members' bytes (in the manifest's
order) and returns the file's bytes; each reproduces, byte for byte, the file that was made by
hand for ../shared/scenes (its SHA-256 in the manifest checks that)."""
import struct
import xml.etree.ElementTree as ElementTree
import zlib


def sibenik_mtllib(obj):
    """The zip's OBJ names an MTL that was not in it; the lleonart1984/Models MTL is used."""
    old, new = b"mtllib untitled.mtl\n", b"mtllib sibenik.mtl\n"
    if old not in obj:
        raise ValueError("no 'mtllib untitled.mtl' line to rename")
    return obj.replace(old, new, 1)


def _c_array(text, name):
    """The comma-separated tokens of `TYPE NAME[] = { ... };` in C source text."""
    body = text.split(name + "[] =", 1)[1].split("{", 1)[1].split("}", 1)[0]
    return [token.strip() for token in body.split(",") if token.strip()]


CONFERENCE_HEADER = (
    "# Conference room (Greg Ward's model, recreated by Kenzie Lamar; see copyright.txt), "
    "converted to OBJ from the conference.bin C arrays in taqu/BoundingVolumeHierarchy "
    "conference.zip\n"
    "# geometry only (no normals/uvs/material groups in the source arrays)\n"
    "mtllib conference.mtl\n"
    "usemtl default\n")


def conference_arrays(source):
    """conference.bin holds the vertex and index arrays as C text: vertices are copied as
    written (no float round trip), indices become 1-based triangles."""
    text = source.decode("ascii")
    coords = _c_array(text, "conference_vertices")
    indices = [int(i) + 1 for i in _c_array(text, "conference_indices")]
    if len(coords) % 3 or len(indices) % 3:
        raise ValueError("conference.bin: arrays are not in threes")
    lines = [CONFERENCE_HEADER]
    lines += ["v %s %s %s\n" % tuple(coords[i:i + 3]) for i in range(0, len(coords), 3)]
    lines += ["f %d %d %d\n" % tuple(indices[i:i + 3]) for i in range(0, len(indices), 3)]
    return "".join(lines).encode("ascii")


def _mitsuba_meshes(data):
    """The meshes of a Mitsuba 0.4 .serialized file (format 0x041C, versions 3 and 4): each a
    2+2 byte header then a zlib stream; the offset table at the end is not needed."""
    meshes, pos = [], 0
    while pos + 4 <= len(data):
        magic, version = struct.unpack_from("<HH", data, pos)
        if magic != 0x041C:
            break
        stream = zlib.decompressobj()
        raw = stream.decompress(data[pos + 4:])
        pos = len(data) - len(stream.unused_data)
        meshes.append(_mitsuba_mesh(raw, version))
    return meshes


def _mitsuba_mesh(raw, version):
    flags, = struct.unpack_from("<I", raw, 0)
    offset = 4
    if version >= 4:  # a name, which version 3 does not have
        offset = raw.index(b"\0", offset) + 1
    vertices, triangles = struct.unpack_from("<QQ", raw, offset)
    offset += 16
    kind, size = ("d", 8) if flags & 0x2000 else ("f", 4)

    def array(count):
        nonlocal offset
        values = struct.unpack_from("<%d%s" % (count, kind), raw, offset)
        offset += count * size
        return values

    mesh = {"p": array(3 * vertices)}
    mesh["n"] = array(3 * vertices) if flags & 0x1 else None
    mesh["uv"] = array(2 * vertices) if flags & 0x2 else None
    if flags & 0x8:
        array(3 * vertices)  # vertex colours: not used
    index = "Q" if vertices > 0xFFFFFFFF else "I"
    mesh["f"] = struct.unpack_from("<%d%s" % (3 * triangles, index), raw, offset)
    return mesh


def mitsuba_sponza(serialized, scene_xml):
    """Every serialized shape of sponza.xml as an OBJ object: its toWorld matrix applied to the
    positions (and its 3x3 part to the normals: a rotation by 1.4e-7 rad here), its BSDF as the
    material, V flipped back to the OBJ convention. Python's %g formatting of double arithmetic
    on the float32 data is what the collection's file used."""
    meshes = _mitsuba_meshes(serialized)
    lines = ["# Dabrovic Sponza, converted to OBJ from the Mitsuba 0.4 scene data "
             "(sponza.serialized + sponza.xml)\n", "mtllib sponza.mtl\n"]
    base = 0
    for shape in ElementTree.fromstring(scene_xml).iter("shape"):
        if shape.get("type") != "serialized":
            continue  # the sphere light
        mesh = meshes[int(shape.find("integer[@name='shapeIndex']").get("value"))]
        m = [float(x) for x in shape.find("transform/matrix").get("value").split()]
        lines.append("o %s\nusemtl %s\n" % (shape.get("id"),
                                            shape.find("ref[@name='bsdf']").get("id")))
        p, n, uv = mesh["p"], mesh["n"], mesh["uv"]
        if n is None or uv is None:
            raise ValueError("sponza.serialized: shape %s lacks normals or UVs" % shape.get("id"))
        count = len(p) // 3
        for x, y, z in zip(p[0::3], p[1::3], p[2::3]):
            lines.append("v %g %g %g\n" % tuple(m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z
                                               + m[4 * r + 3] for r in range(3)))
        lines += ["vt %g %g\n" % (u, 1 - v) for u, v in zip(uv[0::2], uv[1::2])]
        for x, y, z in zip(n[0::3], n[1::3], n[2::3]):
            lines.append("vn %.5g %.5g %.5g\n" % tuple(
                m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z for r in range(3)))
        f = [base + i + 1 for i in mesh["f"]]
        lines += ["f %d/%d/%d %d/%d/%d %d/%d/%d\n" % (a, a, a, b, b, b, c, c, c)
                  for a, b, c in zip(f[0::3], f[1::3], f[2::3])]
        base += count
    return "".join(lines).encode("ascii")


# name in the manifest -> (function, what it does, for assets/SCENES.md)
CONVERTERS = {
    "sibenik-mtllib": (sibenik_mtllib, "its `mtllib untitled.mtl` line renamed to sibenik.mtl"),
    "conference-arrays": (conference_arrays,
                          "C arrays written out as `v`/`f` lines (vertices as written)"),
    "mitsuba-sponza": (mitsuba_sponza,
                       "the Mitsuba meshes written out as OBJ objects, toWorld applied"),
}
