"""ucsio's disk cache: what a source checkout builds once per machine (the
grammars' tables) and what any install builds once per Python (compiled
regular expressions), in ``$UCSIO_CACHE_DIR``, else ``$XDG_CACHE_HOME/ucsio``,
else ``~/.cache/ucsio``. Everything in it can be deleted at any time: it is
rebuilt, and where it cannot be written ucsio is only slower."""
from __future__ import annotations

import os


def cache_dir() -> str:
    where = os.environ.get("UCSIO_CACHE_DIR")
    if where:
        return where
    base = os.environ.get("XDG_CACHE_HOME")
    if not base:
        home = os.path.expanduser("~")
        if home.startswith("~"):        # no home to expand: never a "~" folder in the cwd
            import tempfile
            user = os.getuid() if hasattr(os, "getuid") else "user"
            return os.path.join(tempfile.gettempdir(), f"ucsio-cache-{user}")
        base = os.path.join(home, ".cache")
    return os.path.join(base, "ucsio")


def write_cache(path: str, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically (a temporary file, then a rename);
    a failure is silent (a read-only home: correct, only slower)."""
    import tempfile

    try:
        folder = os.path.dirname(path)
        os.makedirs(folder, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=os.path.basename(path), suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.replace(tmp, path)
        except BaseException:
            os.unlink(tmp)
            raise
    except OSError:
        pass
