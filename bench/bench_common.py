"""What the benchmark scripts share: the repository root, the scenes and their views, and
running a command that must succeed."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# The OBJ files have no camera: the bunny is framed (frame_box); the buildings are seen from
# inside, as in the paper (framing them from outside shows one flat wall, and Sponza's diffuse
# rays from that wall all escape, leaving no path rays).
SCENES = [  # name, file under --scenes, edacrt_paper_rays camera flags
    ("bunny", "bunny/stanford-bunny.obj", []),
    ("sponza", "sponza/sponza.obj", ["--eye", "14,3,0", "--look-at", "0,5,0", "--fov", "60"]),
    ("sibenik", "sibenik/sibenik.obj",
     ["--eye", "-18,-10,0", "--look-at", "0,-8,0", "--fov", "60"]),
    ("conference", "conference/conference.obj",
     ["--eye", "1500,450,550", "--look-at", "300,100,-200", "--fov", "60"]),
]


def run(command, tool):
    """Runs `command` from the repository root; exits naming `tool` if it fails."""
    result = subprocess.run([str(c) for c in command], cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{tool}: {' '.join(map(str, command))} failed:\n"
                 f"{result.stdout}{result.stderr}")
    return result.stdout
