"""Wheel build hook: ship the grammars' LALR tables beside the grammars.

Lark compiles grammars/*.lark into the tables ucsio.parsing.lalr runs; done
here, an installed ucsio never needs Lark to read a file, not even on its
first run on a machine or under a fresh home folder (ucsio.parsing.grammar
otherwise builds them once and caches them)."""
from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from hatchling.builders.hooks.plugin.interface import BuildHookInterface


class CustomBuildHook(BuildHookInterface):
    def initialize(self, version, build_data):
        if self.target_name != "wheel":
            return
        sys.path.insert(0, str(Path(self.root) / "src"))
        try:
            from ucsio.parsing import grammar
            from ucsio.vendors import GRAMMARS
        finally:
            sys.path.pop(0)
        out = Path(tempfile.mkdtemp(prefix="ucsio-tables-"))
        for path in grammar.write_tables(out, GRAMMARS):
            build_data["force_include"][path] = f"ucsio/grammars/{Path(path).name}"
