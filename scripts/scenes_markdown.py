"""The tables of assets/SCENES.md, generated from assets/scenes.json so that the two cannot drift
(scripts/get-scenes --write-markdown rewrites them; a test checks they are current)."""
import urllib.parse

import scene_convert

BEGIN = "<!-- generated from assets/scenes.json by scripts/get-scenes --write-markdown -->\n"
END = "<!-- end of generated part -->\n"


def origin(url):
    """`owner/repo@commit7` and a link to the repository at that commit, for a GitHub raw URL."""
    parts = urllib.parse.urlsplit(url)
    if parts.netloc != "raw.githubusercontent.com":
        return f"<{url}>"
    owner, repo, commit, path = parts.path.lstrip("/").split("/", 3)
    link = f"https://github.com/{owner}/{repo}/tree/{commit}"
    return f"[{owner}/{repo}@{commit[:7]}]({link}) `{path}`"


def repositories(scene, downloads):
    urls = [e["url"] if "url" in e else downloads[e["download"]]["url"]
            for e in scene["files"] if "repo" not in e]
    seen = []
    for url in urls:
        label = origin(url).rsplit(" ", 1)[0]
        if label not in seen:
            seen.append(label)
    return ", ".join(seen)


def megabytes(size):
    return f"{size / 1e6:.1f} MB" if size >= 1e5 else f"{size / 1e3:.0f} kB"


def how(entry, downloads):
    if "url" in entry:
        return origin(entry["url"])
    if "repo" in entry:
        return f"this repository, `{entry['repo']}`"
    members = ", ".join(f"`{m}`" for m in entry["members"])
    text = f"{members} of download `{entry['download']}`"
    if "convert" in entry:
        text += ": " + scene_convert.CONVERTERS[entry["convert"]][1]
    return text


def generate(manifest):
    downloads, scenes = manifest["downloads"], manifest["scenes"]
    out = [BEGIN, "\n| folder | scene | triangles | files | size | from | made | licence |\n",
           "|---|---|--:|--:|--:|---|---|---|\n"]
    for s in scenes:
        size = sum(e["size"] for e in s["files"])
        out.append(f"| {s['folder']} | {s['title']} | {s['triangles']:,} | {len(s['files'])} | "
                   f"{megabytes(size)} | {repositories(s, downloads)} | {s['made']} | "
                   f"{s['licence']} |\n")
    out.append("\nCredits:\n\n")
    out += [f"* {s['title']}: {s['credit']}.\n" for s in scenes]
    out += ["\nArchives downloaded whole (their members are extracted, some converted):\n\n",
            "| download | size | SHA-256 | from |\n", "|---|--:|---|---|\n"]
    out += [f"| `{name}` | {d['size']:,} | `{d['sha256']}` | {origin(d['url'])} |\n"
            for name, d in downloads.items()]
    out += ["\nEvery file written into the scenes folder:\n\n",
            "| file | size | SHA-256 | from |\n", "|---|--:|---|---|\n"]
    for s in scenes:
        out += [f"| {s['folder']}/{e['name']} | {e['size']:,} | `{e['sha256']}` | "
                f"{how(e, downloads)} |\n" for e in s["files"]]
    out.append("\n" + END)
    return "".join(out)


def current(text):
    """The generated part of SCENES.md's `text`, markers included ("" when absent)."""
    begin, end = text.find(BEGIN), text.find(END)
    return text[begin:end + len(END)] if 0 <= begin < end else ""


def write(path, generated):
    text = path.read_text()
    old = current(text)
    path.write_text(text.replace(old, generated) if old else text + "\n" + generated)
