"""Executes a notebook with nbclient in a scratch folder and fails on
any cell's error (make python-check).  Usage: run_notebook.py NB DIR"""
import sys
import time

import nbclient
import nbformat

nb = nbformat.read(sys.argv[1], as_version=4)
t0 = time.monotonic()
nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                        resources={"metadata": {"path": sys.argv[2]}}).execute()
nbformat.write(nb, f"{sys.argv[2]}/executed.ipynb")
images = sum(1 for c in nb.cells if c.cell_type == "code"
             for o in c.get("outputs", []) if "image/png" in o.get("data", {}))
print(f"notebook: {sys.argv[1]} ran clean in {time.monotonic() - t0:.1f} s, "
      f"{images} figures (executed copy {sys.argv[2]}/executed.ipynb)")
