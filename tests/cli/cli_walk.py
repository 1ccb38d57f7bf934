"""The command tree of ``vbikit.cli.app`` walked (the structural tests of the shared option checks)."""
from __future__ import annotations


def commands(group, prefix: str = ""):
    """(name, click command) of every command under ``group``, subgroups walked."""
    for name, cmd in group.commands.items():
        full = f"{prefix}{name}"
        if hasattr(cmd, "commands"):
            yield from commands(cmd, full + " ")
        else:
            yield full, cmd
