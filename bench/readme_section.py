"""Puts one script's section into bench/README.md, the other scripts' sections kept."""


def splice(readme, heading, section):
    """Puts `section` under `heading` in `readme`, replacing an older one up to the next '## '."""
    text = readme.read_text() if readme.exists() else ""
    lines = text.splitlines()
    if heading in lines:
        start = lines.index(heading)
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")),
                   len(lines))
        lines[start:end] = section.rstrip("\n").splitlines() + ([""] if end < len(lines) else [])
        text = "\n".join(lines) + "\n"
    else:
        text = text.rstrip("\n") + "\n\n" + section
    readme.write_text(text)
