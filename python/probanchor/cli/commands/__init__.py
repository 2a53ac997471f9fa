"""Sub-commands of `anchoring`, one module each (see cli.anchoring_cli)."""
