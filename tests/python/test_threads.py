# SPDX-License-Identifier: BSD-3-Clause
"""Runs in several Python threads give the results of the same runs one by one: coupled runs (each plans its own
FFTW transforms, under the flow kernel's planner lock) and reduced-order runs, mixed on 2 workers."""
import concurrent.futures

import numpy as np

import imcol

TIMINGS = {"run", "wall_time_s", "setup_time_s"}
FLOW_TIMINGS = {"ms_per_step", "start_up_time_s", "flow_time_s", "ode_time_s", "flow_share", "ode_share", "fields_time_s", "cpu_time_s"}


def comparable(r):
    """The run's summary less its timings, and its trajectory."""
    d = {k: v for k, v in r.to_dict().items() if k not in TIMINGS}
    if "flow" in d:
        d["flow"] = {k: v for k, v in d["flow"].items() if k not in FLOW_TIMINGS}
    return d, r.trajectory


def jobs():
    coupled = [imcol.Scene.load(name).set("flow.cells_per_diameter", cpd)
               for name, cpd in [("coupled/gg3462", 8), ("coupled/gondret_st27", 8), ("coupled/free_fall_re20", 8),
                                 ("coupled/gg3462", 12)]]
    reduced = [imcol.Scene.load("default").set("sphere[0].velocity", v) for v in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6)]
    reduced += [imcol.Scene.load("default").set("effects", ["drag", "lubrication", "added_mass", "history", "elastic"]),
                imcol.Scene.load("default").set("fluid.viscosity", 0.05)]
    # interleaved, so that coupled runs overlap each other and reduced-order runs
    out = []
    for k in range(max(len(coupled), len(reduced))):
        out += coupled[k:k + 1] + reduced[k:k + 1] if k < len(coupled) else reduced[k:k + 1]
    return out


def test_threads_give_the_runs_one_by_one():
    scenes = jobs()
    assert len(scenes) == 12
    serial = [comparable(imcol.run(s)) for s in scenes]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(pool.map(lambda s: comparable(imcol.run(s)), scenes))
    assert sum("flow" in d for d, _ in serial) == 4
    for (ds, ts), (dt, tt) in zip(serial, threaded):
        assert dt == ds, ds["scene"]
        assert list(tt) == list(ts)
        for col in ts:
            np.testing.assert_array_equal(tt[col], ts[col], err_msg=f"{ds['scene']}: {col}")
