# SPDX-License-Identifier: BSD-3-Clause
"""Executes a notebook (nbclient, the interpreter's own ipykernel) and checks it: the copy in the repository has no
outputs, every cell runs without error, and each plotting cell shows a picture.

    run_notebook.py NOTEBOOK --out EXECUTED.ipynb
    run_notebook.py NOTEBOOK --strip        # clears the stored copy's outputs and execution counts, in place
"""
import argparse
import pathlib
import sys

import nbformat
from nbclient import NotebookClient

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("notebook", type=pathlib.Path)
group = parser.add_mutually_exclusive_group(required=True)
group.add_argument("--out", type=pathlib.Path, help="where the executed copy is written")
group.add_argument("--strip", action="store_true", help="clear the notebook's outputs in place and stop")
parser.add_argument("--timeout", type=int, default=300, help="seconds per cell")
args = parser.parse_args()

nb = nbformat.read(args.notebook, as_version=4)
code = [c for c in nb.cells if c.cell_type == "code"]
if args.strip:
    for c in code:
        c.outputs, c.execution_count = [], None
        c.metadata.pop("execution", None)  # nbclient's timings
    nbformat.write(nb, args.notebook)
    sys.exit(0)
stored = [i for i, c in enumerate(code) if c.outputs or c.execution_count is not None or "execution" in c.metadata]
if stored:
    sys.exit(f"{args.notebook}: code cells {stored} carry outputs, execution counts or timings: strip them before committing")

# Debian's python3-ipykernel: the kernel "python3" is /usr/bin/python3; it inherits this process's environment.
client = NotebookClient(nb, timeout=args.timeout, kernel_name="python3",
                        resources={"metadata": {"path": str(args.notebook.parent)}})
client.execute()
args.out.parent.mkdir(parents=True, exist_ok=True)
nbformat.write(nb, args.out)

missing = [i for i, c in enumerate(code) if "plt.show()" in c.source
           and not any("image/png" in o.get("data", {}) for o in c.outputs)]
if missing:
    sys.exit(f"{args.notebook}: plotting cells {missing} showed no picture")
print(f"{args.notebook.name}: {len(code)} code cells ran; executed copy {args.out}")
