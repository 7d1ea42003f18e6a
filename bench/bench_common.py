"""What the benchmark scripts share: the repository root, the scenes each one measures (the
lists of assets/scenes.json, the one scene list, also read by `edacrt bench`) and their views,
and running a command that must succeed."""
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import NamedTuple

ROOT = Path(__file__).resolve().parent.parent
MANIFEST = ROOT / "assets" / "scenes.json"
# The large scenes: $EDACRT_SCENES, else ../shared/scenes beside the repository (each script's
# --scenes default).
SCENES_DIR = Path(os.environ.get("EDACRT_SCENES", ROOT.parent / "shared" / "scenes"))


class Scene(NamedTuple):
    name: str  # as --scene and the lists say it: the manifest's "name", else the folder
    relative: Path  # folder/file, under assets/ when bundled, else under the scenes folder
    camera_flags: list  # edacrt_paper_rays flags from "paper_camera" (empty: its own view)

    def path(self, scenes_dir):
        """The scene's file: bundled under assets/ when it is there, else under `scenes_dir`."""
        bundled = ROOT / "assets" / self.relative
        return bundled if bundled.is_file() else Path(scenes_dir) / self.relative


def _camera_flags(camera):
    """The OBJ files have no camera: objects are framed (frame_box); the buildings are seen from
    inside, as in the paper (framing them from outside shows one flat wall, and Sponza's diffuse
    rays from that wall all escape, leaving no path rays)."""
    if not camera:
        return []
    xyz = lambda v: ",".join(f"{c:g}" for c in v)  # noqa: E731
    return ["--eye", xyz(camera["eye"]), "--look-at", xyz(camera["look_at"]),
            "--fov", f"{camera['fov']:g}"]


def scene_list(name):
    """The scenes of the manifest's list `name` ("paper", "report", ...), in its order."""
    manifest = json.loads(MANIFEST.read_text())
    scenes = {s.get("name", s["folder"]): s for s in manifest["scenes"]}
    return [Scene(n, Path(scenes[n]["folder"]) / scenes[n]["scene"],
                  _camera_flags(scenes[n].get("paper_camera")))
            for n in manifest["lists"][name]["scenes"]]


def run(command, tool):
    """Runs `command` from the repository root; exits naming `tool` if it fails."""
    result = subprocess.run([str(c) for c in command], cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{tool}: {' '.join(map(str, command))} failed:\n"
                 f"{result.stdout}{result.stderr}")
    return result.stdout
