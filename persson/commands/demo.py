"""``persson demo``: the main job on the shipped example (writes CSV, PNG and prints where)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

NAME = "demo"
HELP = "run the workflow on the shipped example (synthetic road + synthetic tread compound)"


def add_arguments(p):
    p.add_argument("-o", "--output-dir", default="persson-demo", help="folder for the outputs (default ./persson-demo)")


def run(args) -> int:
    import materials
    import surfaces

    from ..io import write_csv
    from ..model import Model
    from ..plots import plot_friction, save_figure

    out = Path(args.output_dir)
    surface = surfaces.example_road()
    material = materials.example_tread()
    model = Model(surface, material)
    speeds = np.geomspace(1e-8, 10.0, 100)
    r = model.friction(speeds, temperature=20.0, pressure=0.3e6)
    csv = write_csv(out / "friction_vs_speed.csv", r.as_table(),
                    comments=("persson demo: example_road (synthetic) + example_tread (synthetic)",
                              "T0 = 20 C, sigma0 = 0.3 MPa, baseline (hysteresis + contact area)"))
    png = save_figure(plot_friction(r, title="example tread on example road, 20 C, 0.3 MPa"),
                      out / "friction_vs_speed.png")
    i = int(np.argmax(np.atleast_1d(r.mu)))
    print(f"peak mu = {np.atleast_1d(r.mu)[i]:.3f} at v = {speeds[i]:.3g} m/s; "
          f"A/A0 at 1 m/s = {np.interp(0.0, np.log10(speeds), np.atleast_1d(r.contact_area)):.4f}")
    print(f"wrote {csv.resolve()}")
    print(f"wrote {png.resolve()}")
    return 0
