"""scripts/get-scenes against local mirrors built here from small files (no network): fetching
and checking, a corrupted file, an unreachable host, the conversions, and assets/SCENES.md
agreeing with assets/scenes.json. Run by CTest; `python3 tests/get_scenes_test.py -v` alone."""
import functools
import hashlib
import http.server
import io
import json
import os
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest
import zipfile
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "scripts" / "get-scenes"
sys.dont_write_bytecode = True  # no __pycache__ in the source tree from CTest
sys.path.insert(0, str(ROOT / "scripts"))
import scene_convert  # noqa: E402
import scenes_markdown  # noqa: E402

RAW = "https://raw.githubusercontent.com/owner/repo/0123456789abcdef0123456789abcdef01234567/"


def entry(name, data, **source):
    return dict(name=name, size=len(data), sha256=hashlib.sha256(data).hexdigest(), **source)


def zip_bytes(members):
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as z:
        for name, data in members.items():
            z.writestr(name, data)
    return buffer.getvalue()


def unused_port():
    """A local port nothing listens on: a connection is refused at once."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Mirror:
    """A temporary directory holding a small manifest, the files it names laid out as
    HOST/PATH (what --mirror reads) and an empty scenes folder."""

    OBJ = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    ZIPPED_OBJ = b"mtllib untitled.mtl\n" + OBJ

    def __init__(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)
        self.dest = self.dir / "scenes"
        archive = zip_bytes({"inner/tri.obj": self.ZIPPED_OBJ, "inner/LICENCE": b"free\n"})
        self.put(RAW + "tri.obj", self.OBJ)
        self.put(RAW + "tri.zip", archive)
        converted = scene_convert.sibenik_mtllib(self.ZIPPED_OBJ)
        source = ROOT / "assets" / "cornell-box" / "SOURCE.txt"
        self.manifest = {
            "downloads": {"tri-zip": entry("tri.zip", archive, url=RAW + "tri.zip")},
            "scenes": [
                {"folder": "plain", "scene": "tri.obj", "title": "T", "triangles": 1,
                 "credit": "c", "licence": "l", "made": "m",
                 "files": [entry("tri.obj", self.OBJ, url=RAW + "tri.obj"),
                           entry("SOURCE.txt", source.read_bytes(),
                                 repo="assets/cornell-box/SOURCE.txt")]},
                {"folder": "zipped", "scene": "tri.obj", "title": "Z", "triangles": 1,
                 "credit": "c", "licence": "l", "made": "m",
                 "files": [entry("tri.obj", converted, download="tri-zip",
                                 members=["inner/tri.obj"], convert="sibenik-mtllib"),
                           entry("sub/LICENCE", b"free\n", download="tri-zip",
                                 members=["inner/LICENCE"])]},
            ]}
        for d in self.manifest["downloads"].values():
            del d["name"]
        self.write_manifest()

    def put(self, url, data):
        path = self.dir / "mirror" / url.split("://", 1)[1]
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)

    def write_manifest(self):
        (self.dir / "scenes.json").write_text(json.dumps(self.manifest))

    def run(self, *args, mirror=True):
        command = [sys.executable, str(SCRIPT), "--manifest", str(self.dir / "scenes.json"),
                   "--dest", str(self.dest)]
        if mirror:
            command += ["--mirror", str(self.dir / "mirror")]
        return subprocess.run(command + list(args), capture_output=True, text=True, timeout=60)

    def files(self):
        return sorted(str(p.relative_to(self.dest)) for p in self.dest.rglob("*") if p.is_file())


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


class Fetching(unittest.TestCase):
    def setUp(self):
        self.m = Mirror()
        self.addCleanup(self.m.tmp.cleanup)

    def test_fetches_checks_and_skips_what_is_present(self):
        result = self.m.run()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(self.m.files(), ["plain/SOURCE.txt", "plain/tri.obj",
                                          "zipped/sub/LICENCE", "zipped/tri.obj"])
        self.assertEqual((self.m.dest / "plain" / "tri.obj").read_bytes(), Mirror.OBJ)
        self.assertTrue((self.m.dest / "zipped" / "tri.obj").read_bytes()
                        .startswith(b"mtllib sibenik.mtl\n"))
        self.assertIn("4 files fetched, 0 already present", result.stdout)
        again = self.m.run()
        self.assertIn("0 files fetched, 4 already present", again.stdout)
        listed = self.m.run("--list")
        self.assertRegex(listed.stdout, r"plain .* present")

    def test_file_urls_and_only(self):
        for s in self.m.manifest["scenes"]:
            for e in s["files"]:
                if "url" in e:
                    e["url"] = (self.m.dir / "mirror" / e["url"].split("://")[1]).as_uri()
        self.m.write_manifest()
        result = self.m.run("--only", "plain", mirror=False)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(self.m.files(), ["plain/SOURCE.txt", "plain/tri.obj"])
        unknown = self.m.run("--only", "nope")
        self.assertEqual(unknown.returncode, 1)
        self.assertIn("unknown scene nope", unknown.stderr)

    def test_a_corrupted_file_is_an_error_and_leaves_nothing(self):
        self.m.put(RAW + "tri.obj", Mirror.OBJ.replace(b"1 0 0", b"2 0 0"))
        result = self.m.run("--only", "plain")
        self.assertEqual(result.returncode, 1)
        self.assertIn("checksum mismatch", result.stderr)
        self.assertIn("tri.obj", result.stderr)
        self.assertEqual(self.m.files(), [])  # neither the file nor its temporary

    def test_a_corrupted_archive_is_an_error(self):
        self.m.put(RAW + "tri.zip", zip_bytes({"inner/tri.obj": b"other"}))
        result = self.m.run("--only", "zipped")
        self.assertEqual(result.returncode, 1)
        self.assertIn("checksum mismatch", result.stderr)
        self.assertEqual(self.m.files(), [])

    def test_a_file_longer_than_listed_is_cut_short(self):
        self.m.put(RAW + "tri.obj", Mirror.OBJ * 1000)
        result = self.m.run("--only", "plain")
        self.assertEqual(result.returncode, 1)
        self.assertIn("more than the manifest's", result.stderr)
        self.assertEqual(self.m.files(), [])

    def test_a_wrong_file_already_there_is_replaced(self):
        target = self.m.dest / "plain" / "tri.obj"
        target.parent.mkdir(parents=True)
        target.write_bytes(b"stale")
        result = self.m.run("--only", "plain")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(target.read_bytes(), Mirror.OBJ)

    def test_an_unreachable_host_says_offline(self):
        port = unused_port()
        result = self.m.run("--mirror", f"http://127.0.0.1:{port}", mirror=False)
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"cannot reach 127.0.0.1:{port}: ", result.stderr)
        self.assertIn("are you offline?", result.stderr)
        self.assertEqual(self.m.files(), [])

    def test_over_http_and_a_missing_file(self):
        handler = functools.partial(QuietHandler, directory=str(self.m.dir / "mirror"))
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        self.addCleanup(server.server_close)
        self.addCleanup(server.shutdown)
        url = f"http://127.0.0.1:{server.server_address[1]}"
        result = self.m.run("--mirror", url, mirror=False)
        self.assertEqual(result.returncode, 0, result.stderr)
        (self.m.dest / "plain" / "tri.obj").unlink()
        (self.m.dir / "mirror" / RAW.split("://")[1] / "tri.obj").unlink()
        missing = self.m.run("--mirror", url, mirror=False)
        self.assertEqual(missing.returncode, 1)
        self.assertIn("the server answered 404", missing.stderr)


class StallingHandler(http.server.BaseHTTPRequestHandler):
    """Sends half of a promised body, then waits: a download that is still under way."""

    def do_GET(self):
        self.send_response(200)
        self.send_header("Content-Length", str(len(Mirror.OBJ)))
        self.end_headers()
        self.wfile.write(Mirror.OBJ[:10])
        self.wfile.flush()
        time.sleep(30)

    def log_message(self, *args):
        pass


class Interrupting(unittest.TestCase):
    """What an interrupted, killed or offline run leaves: no temporary files, no empty folders,
    and a FIFO in a mirror is refused rather than waited on."""

    def setUp(self):
        self.m = Mirror()
        self.addCleanup(self.m.tmp.cleanup)

    def everything(self):
        return sorted(str(p.relative_to(self.m.dest)) for p in self.m.dest.rglob("*")) \
            if self.m.dest.exists() else []

    def test_sigterm_removes_the_part_file(self):
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), StallingHandler)
        server.daemon_threads = True
        threading.Thread(target=server.serve_forever, daemon=True).start()
        self.addCleanup(server.server_close)
        self.addCleanup(server.shutdown)
        command = [sys.executable, str(SCRIPT), "--manifest", str(self.m.dir / "scenes.json"),
                   "--dest", str(self.m.dest), "--only", "plain",
                   "--mirror", f"http://127.0.0.1:{server.server_address[1]}"]
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True)
        deadline = time.monotonic() + 20
        while not list(self.m.dest.rglob("*.part")) and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertTrue(list(self.m.dest.rglob("*.part")), "the download never started")
        process.send_signal(signal.SIGTERM)
        _, stderr = process.communicate(timeout=20)
        self.assertEqual(process.returncode, 128 + signal.SIGTERM, stderr)
        self.assertIn("get-scenes: terminated", stderr)
        self.assertEqual(self.everything(), [])

    def test_the_next_run_removes_part_files_a_killed_run_left(self):
        folder = self.m.dest / "plain"
        folder.mkdir(parents=True)
        # A process id above any pid_max, so certainly not running; and the older naming.
        for name in [".tri.obj.4999999.abc123.part", ".tri.obj.k2j_x9.part"]:
            (folder / name).write_bytes(b"half")
        result = self.m.run("--only", "plain")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("removed 2 temporary files", result.stdout)
        self.assertEqual(self.everything(), ["plain", "plain/SOURCE.txt", "plain/tri.obj"])

    def test_a_killed_runs_folder_goes_with_its_part_files_when_the_next_run_is_offline(self):
        # A killed run made plain/ and zipped/sub/ for its downloads; the next run, offline,
        # removes the part files and must not leave their folders empty.
        for folder in [self.m.dest / "plain", self.m.dest / "zipped" / "sub"]:
            folder.mkdir(parents=True)
            (folder / ".f.4999999.abc123.part").write_bytes(b"half")
        result = self.m.run("--mirror", f"http://127.0.0.1:{unused_port()}", mirror=False)
        self.assertEqual(result.returncode, 1)
        self.assertIn("removed 2 temporary files", result.stdout)
        self.assertEqual(self.everything(), [])
        self.assertTrue(self.m.dest.is_dir(), "the scenes folder itself is the user's")

    def test_offline_leaves_no_empty_folders(self):
        result = self.m.run("--mirror", f"http://127.0.0.1:{unused_port()}", mirror=False)
        self.assertEqual(result.returncode, 1)
        self.assertIn("are you offline?", result.stderr)
        self.assertEqual(self.everything(), [])
        self.assertFalse(self.m.dest.exists())

    def test_a_fifo_in_the_mirror_is_refused(self):
        path = self.m.dir / "mirror" / RAW.split("://")[1] / "tri.obj"
        path.unlink()
        os.mkfifo(path)
        result = self.m.run("--only", "plain")
        self.assertEqual(result.returncode, 1)
        self.assertIn("not a regular file", result.stderr)
        self.assertEqual(self.everything(), [])


def mitsuba_mesh(positions, normals, uvs, faces):
    """A version-3 Mitsuba .serialized mesh (float32 positions, normals and UVs)."""
    body = struct.pack("<IQQ", 0x1003, len(positions) // 3, len(faces) // 3)
    for values in (positions, normals, uvs):
        body += struct.pack("<%df" % len(values), *values)
    body += struct.pack("<%dI" % len(faces), *faces)
    return struct.pack("<HH", 0x041C, 3) + zlib.compress(body)


class Converting(unittest.TestCase):
    def test_conference_arrays(self):
        source = (b"float conference_vertices[] =\n{\n    1.5, -2, 3e-05,\n    4, 5, 6, 7, 8, 9\n};"
                  b"\n\nunsigned int conference_indices[] =\n{\n    0, 1, 2, 2, 1, 0\n};\n")
        obj = scene_convert.conference_arrays(source).decode()
        self.assertTrue(obj.startswith(scene_convert.CONFERENCE_HEADER))
        self.assertTrue(obj.endswith("v 1.5 -2 3e-05\nv 4 5 6\nv 7 8 9\nf 1 2 3\nf 3 2 1\n"))

    def test_mitsuba_meshes_with_their_transform(self):
        serialized = (mitsuba_mesh([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 0, 1] * 3,
                                   [0, 0, 1, 0, 0, 0.25], [0, 1, 2])
                      + mitsuba_mesh([0, 0, 0, 0, 0, 1, 1, 0, 0], [0, 1, 0] * 3,
                                     [0, 0, 0, 0, 0, 0], [0, 1, 2]))
        xml = b"""<scene><shape type="sphere"/>
            <shape type="serialized" id="b"><integer name="shapeIndex" value="1"/>
            <transform name="toWorld"><matrix value="1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1"/>
            </transform><ref name="bsdf" id="stone"/></shape>
            <shape type="serialized" id="a"><integer name="shapeIndex" value="0"/>
            <transform name="toWorld"><matrix value="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/>
            </transform><ref name="bsdf" id="wood"/></shape></scene>"""
        lines = scene_convert.mitsuba_sponza(serialized, xml).decode().splitlines()
        self.assertEqual(lines[2:6], ["o b", "usemtl stone", "v 10 0 0", "v 10 0 1"])
        self.assertIn("vn 0 1 0", lines)
        self.assertEqual(lines[lines.index("o a") + 5], "vt 0 1")  # V flipped
        self.assertIn("vt 0 0.75", lines)
        self.assertEqual(lines[-1], "f 4/4/4 5/5/5 6/6/6")  # numbered after the first object

    def test_sibenik_needs_its_line(self):
        with self.assertRaises(ValueError):
            scene_convert.sibenik_mtllib(b"mtllib other.mtl\n")


class Manifest(unittest.TestCase):
    manifest = json.loads((ROOT / "assets" / "scenes.json").read_text())

    def test_scenes_md_is_generated_from_it(self):
        text = (ROOT / "assets" / "SCENES.md").read_text()
        self.assertEqual(scenes_markdown.current(text), scenes_markdown.generate(self.manifest),
                         "assets/SCENES.md is stale: run scripts/get-scenes --write-markdown")

    def test_entries_are_complete(self):
        folders = [s["folder"] for s in self.manifest["scenes"]]
        self.assertEqual(len(folders), len(set(folders)))
        for s in self.manifest["scenes"]:
            names = [e["name"] for e in s["files"]]
            self.assertIn(s["scene"], names)
            self.assertEqual(len(names), len(set(names)))
            for e in s["files"]:
                self.assertRegex(e["sha256"], "^[0-9a-f]{64}$")
                self.assertNotIn("..", Path(e["name"]).parts)
                kinds = [k for k in ("url", "repo", "download") if k in e]
                self.assertEqual(len(kinds), 1, e)
                if "url" in e:  # pinned: a full commit hash in the path
                    self.assertRegex(e["url"], r"^https://raw\.githubusercontent\.com/"
                                               r"[^/]+/[^/]+/[0-9a-f]{40}/")
                if "repo" in e:
                    data = (ROOT / e["repo"]).read_bytes()
                    self.assertEqual(hashlib.sha256(data).hexdigest(), e["sha256"], e["repo"])
                if "download" in e:
                    self.assertIn(e["download"], self.manifest["downloads"])
                    self.assertIn(e.get("convert", "sibenik-mtllib"), scene_convert.CONVERTERS)

    def test_bench_lists_as_the_scripts_read_them(self):
        sys.path.insert(0, str(ROOT / "bench"))
        import bench_common  # noqa: E402
        for name in ("bench", "bench_dynamic", "paper", "report", "deviations", "trace_benchmark"):
            scenes = bench_common.scene_list(name)
            self.assertTrue(scenes, name)
            for s in scenes:
                self.assertIn(len(s.camera_flags), (0, 6), s)
        for s in bench_common.scene_list("report"):  # bench/report.py needs them bundled
            self.assertTrue((ROOT / "assets" / s.relative).is_file(), s)
        sponza = next(s for s in bench_common.scene_list("paper") if s.name == "sponza")
        self.assertEqual(sponza.camera_flags,
                         ["--eye", "14,3,0", "--look-at", "0,5,0", "--fov", "60"])

    def test_scenes_already_there_match(self):
        result = subprocess.run([sys.executable, str(SCRIPT), "--list"], capture_output=True,
                                text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("wrong checksum", result.stdout)


if __name__ == "__main__":
    unittest.main()
