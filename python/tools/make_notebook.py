"""Writes examples/straylight.ipynb (cells below, no outputs): run once
with nbformat after editing; `make python-check` executes the notebook."""
import sys

import nbformat as nbf

md, code = nbf.v4.new_markdown_cell, nbf.v4.new_code_cell
cells = [
    md("# straylight from Python\n\n"
       "A baffle traced, its exclusion angles, detector frames with the Sun "
       "at 35°, and a diagnosis of a measured curve — each one call of the "
       "`straylight` package (`python3 -m pip install ./python`), which runs "
       "the same library code as the `stray` command: the same seed and "
       "threads give the same numbers (`docs/python.md`)."),
    code("import numpy as np\n"
         "import pandas as pd\n"
         "import matplotlib\n"
         "import matplotlib.pyplot as plt\n"
         "import straylight as sl\n"
         "print('straylight', sl.__version__)"),
    md("## Trace the reference baffle\n\n"
       "`ref4` is the built-in four-vane baffle.  The curve comes back as "
       "numpy arrays (alpha is a power ratio, 1 on axis; sigma one standard "
       "error), with the scatter orders as further columns."),
    code("baffle = sl.trace('ref4', angles='0:20:2,20:90:2', rays=100_000,\n"
         "                  seed=1, threads=2)\n"
         "system = sl.trace('ref4', angles='0:20:2,20:90:2', rays=100_000,\n"
         "                  seed=1, threads=2, lens='ideal:10')\n"
         "print(baffle, baffle.meta['seed'], baffle.meta['rays'])\n"
         "fig, ax = plt.subplots(figsize=(7, 4))\n"
         "for c, name in ((baffle, 'baffle'), (system, 'baffle + ideal lens')):\n"
         "    ok = c.alpha > 0\n"
         "    ax.errorbar(c.theta_deg[ok], c.alpha[ok], c.sigma[ok], fmt='.-',\n"
         "                label=name)\n"
         "ax.set_yscale('log'); ax.set_xlabel('Sun angle off boresight [deg]')\n"
         "ax.set_ylabel('alpha'); ax.legend(); ax.grid(True, which='both', alpha=.3)"),
    md("The curve file is the CSV of `docs/formats.md`; pandas reads it with "
       "`comment='#'`."),
    code("system.to_csv('ref4_system.csv')\n"
         "df = pd.read_csv('ref4_system.csv', comment='#')\n"
         "df.head()"),
    md("## Exclusion angles\n\n"
       "The smallest Sun and Moon angles beyond which the curve stays below "
       "`alpha_required` (5 false stars per image on the st16-like sensor). "
       "The bare baffle does not exclude the Sun inside its curve; with the "
       "lens it does."),
    code("ex = sl.exclusion(system)\n"
         "print('Sun  %.2f deg, Moon %.2f deg' % (ex['sun_deg'], ex['moon_deg']))\n"
         "print('bare baffle: Sun', sl.exclusion(baffle)['sun_deg'])\n"
         "fig, ax = plt.subplots(figsize=(7, 4))\n"
         "ok = system.alpha > 0\n"
         "ax.semilogy(system.theta_deg[ok], system.alpha[ok], '.-', label='system')\n"
         "ax.axhline(ex['sun']['alpha_required'], color='C3', ls='--',\n"
         "           label='alpha_required (Sun)')\n"
         "ax.axvline(ex['sun_deg'], color='C3', label='Sun exclusion')\n"
         "ax.axvline(ex['moon_deg'], color='C2', label='Moon exclusion')\n"
         "ax.set_xlabel('angle [deg]'); ax.set_ylabel('alpha'); ax.legend()"),
    md("## Frames with the Sun at 35°\n\n"
       "Rendered 256 × 256 windows (stray light, a synthetic star field, "
       "camera noise), the star detectors run on them, and false stars "
       "against the FDR model.  Through the system (baffle and lens): the "
       "bare baffle's light at 35° would fill every pixel to the ADC's full "
       "scale, which `stray frames` refuses.  `f.images` is a uint16 array "
       "over the library's own buffer — no copy."),
    code("f = sl.frames(curve=system, theta=35, frames=2, window=256, seed=7)\n"
         "print(f.images.shape, f.images.dtype, 'owns its data:',\n"
         "      f.images.flags.owndata)\n"
         "s = f.summary\n"
         "print('false stars per image %.1f (model %.1f)' %\n"
         "      (s['false_stars_per_image'], s['model_fdr_extended']))\n"
         "fig, axs = plt.subplots(1, 2, figsize=(9, 4))\n"
         "for ax, img in zip(axs, f.images):\n"
         "    im = ax.imshow(img, cmap='magma',\n"
         "                   norm=matplotlib.colors.LogNorm(vmin=max(img.min(), 1)))\n"
         "    ax.set_title('frame, Sun at 35 deg')\n"
         "fig.colorbar(im, ax=axs, label='counts')"),
    md("## A diagnosis\n\n"
       "A \"measured\" curve: the baffle with an 8 % coating (the model "
       "assumes 4 %) and 5 % measurement noise.  The diagnosis names the "
       "cause, and its JSON carries the model curves before and after."),
    code("truth = sl.trace('ref4', angles='0:10:5,10:60:2.5', rays=60_000,\n"
         "                 seed=2, threads=2, set={'reflectance': 0.08})\n"
         "rng = np.random.default_rng(1)\n"
         "keep = truth.alpha > 0\n"
         "theta, alpha = truth.theta_deg[keep], truth.alpha[keep]\n"
         "sigma = np.hypot(0.05 * alpha, truth.sigma[keep])\n"
         "sigma[theta == 0] = 0  # the normalisation row\n"
         "meas = alpha * (1 + 0.05 * rng.standard_normal(alpha.size) * (theta > 0))\n"
         "d = sl.diagnose((theta, meas, sigma), scene='ref4', rays=20_000,\n"
         "                threads=2, causes='reflectance,floor')\n"
         "for c in d['causes']:\n"
         "    print(c['name'], c['params'], c['intervals'])\n"
         "cv = d['curves']\n"
         "fig, ax = plt.subplots(figsize=(7, 4))\n"
         "ax.errorbar(cv['theta_deg'], cv['measured'], cv['sigma'], fmt='k.',\n"
         "            label='measured')\n"
         "ax.semilogy(cv['theta_deg'], cv['model_before'], label='model before')\n"
         "ax.semilogy(cv['theta_deg'], cv['model_after'], label='model after')\n"
         "ax.set_xlabel('angle [deg]'); ax.set_ylabel('alpha'); ax.legend()\n"
         "print('Sun exclusion before %s, after %s' % (d['sun_deg_before'],\n"
         "                                            d['sun_deg_after']))"),
]
nb = nbf.v4.new_notebook(cells=cells)
nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                             "language": "python"}
nbf.write(nb, sys.argv[1])
