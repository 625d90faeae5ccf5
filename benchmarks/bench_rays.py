"""Ray integrators on a hot road (issue: foundation benchmark).

10 000 rays from an eye 1.5 m above a hot road (PhysicalAtmosphere, surface_dt = 10 K,
surface_depth = 0.1 m), elevations evenly from -1 deg to +1 deg, 2 km each (or until they reach
the road, stop_height = 0). Time per ray, field evaluations per ray, and end-point error against a
converged reference (stratified at tol 1e-9 m) for:
  rk4 at step 0.3 m (the original editor's setting), rk45 at tol 1 mm, and the ElevationTable at
  tol 1 mm (build time included, amortised over the rays).
Goals: rk45 >= 10x faster than rk4 at 0.3 m; the table >= 50x faster than rk45 at equal error.

    python benchmarks/bench_rays.py [--rays N]     -> benchmarks/results/rays.json
"""

from __future__ import annotations

import argparse

import numpy as np
from _common import timed, write_results

import refracta

EYE_HEIGHT = 1.5
LENGTH = 2000.0


def main(rays: int = 10_000) -> dict:
    field = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    elevations = np.linspace(-1.0, 1.0, rays)
    e = np.radians(elevations)
    directions = np.stack([np.cos(e), np.sin(e), np.zeros_like(e)], axis=1)
    origin = np.array([0.0, EYE_HEIGHT, 0.0])
    common = dict(max_length=LENGTH, stop_height=0.0)

    reference, t_ref = timed(refracta.trace_rays, field, origin, directions, trace="stratified", tol=1e-9, **common)

    def error_of(batch):
        err = np.linalg.norm(batch.end_points - reference.end_points, axis=1)
        return {
            "max_error_m": float(err.max()),
            "p99_error_m": float(np.quantile(err, 0.99)),
            "median_error_m": float(np.median(err)),
        }

    rows = {}
    rk4, t = timed(refracta.trace_rays, field, origin, directions, trace="rk4", step=0.3, **common)
    rows["rk4_step_0.3m"] = {
        "seconds": t,
        "us_per_ray": 1e6 * t / rays,
        "evaluations_per_ray": float(rk4.evaluations.mean()),
        **error_of(rk4),
    }
    rk45, t = timed(refracta.trace_rays, field, origin, directions, trace="rk45", tol=1e-3, **common)
    rows["rk45_tol_1mm"] = {
        "seconds": t,
        "us_per_ray": 1e6 * t / rays,
        "evaluations_per_ray": float(rk45.evaluations.mean()),
        **error_of(rk45),
    }
    strat, t = timed(refracta.trace_rays, field, origin, directions, trace="stratified", tol=1e-3, **common)
    rows["stratified_tol_1mm"] = {
        "seconds": t,
        "us_per_ray": 1e6 * t / rays,
        "evaluations_per_ray": float(strat.evaluations.mean()),
        **error_of(strat),
    }

    # rk45 at equal error: the loosest tolerance whose worst end-point error is within the table's.
    table_probe = refracta.ElevationTable(field, EYE_HEIGHT, -1.0, 1.0, tol=1e-3, **common)
    table_error = error_of(table_probe.ends(elevations))["max_error_m"]
    for tol in (1e-4, 3e-5, 1e-5, 3e-6, 1e-6, 1e-7):
        batch, t = timed(refracta.trace_rays, field, origin, directions, trace="rk45", tol=tol, **common)
        if error_of(batch)["max_error_m"] <= table_error:
            break
    rows["rk45_at_table_error"] = {
        "tol": tol,
        "seconds": t,
        "us_per_ray": 1e6 * t / rays,
        "evaluations_per_ray": float(batch.evaluations.mean()),
        **error_of(batch),
    }

    table, t_build = timed(refracta.ElevationTable, field, EYE_HEIGHT, -1.0, 1.0, tol=1e-3, **common)
    ends, t_query = timed(table.ends, elevations)
    t_table = t_build + t_query
    rows["elevation_table_tol_1mm"] = {
        "seconds": t_table,
        "build_seconds": t_build,
        "query_seconds": t_query,
        "us_per_ray": 1e6 * t_table / rays,
        "evaluations_per_ray": table.evaluations / rays,
        "traced_elevations": table.size,
        "exact_intervals": table.exact_intervals,
        **error_of(ends),
    }

    result = {
        "setup": {
            "rays": rays,
            "eye_height_m": EYE_HEIGHT,
            "length_m": LENGTH,
            "elevations_deg": [-1.0, 1.0],
            "field": repr(field),
            "reference": "stratified, tol 1e-9 m",
            "reference_seconds": t_ref,
        },
        "methods": rows,
        "ratios": {
            "rk4_over_rk45_time": rows["rk4_step_0.3m"]["seconds"] / rows["rk45_tol_1mm"]["seconds"],
            "rk45_over_table_time": rows["rk45_tol_1mm"]["seconds"] / rows["elevation_table_tol_1mm"]["seconds"],
            "rk45_at_equal_error_over_table_time": rows["rk45_at_table_error"]["seconds"]
            / rows["elevation_table_tol_1mm"]["seconds"],
        },
        "goals": {"rk45_10x_faster_than_rk4": None, "table_50x_faster_than_rk45": None},
    }
    result["goals"]["rk45_10x_faster_than_rk4"] = result["ratios"]["rk4_over_rk45_time"] >= 10
    result["goals"]["table_50x_faster_than_rk45"] = result["ratios"]["rk45_at_equal_error_over_table_time"] >= 50
    return result


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rays", type=int, default=10_000)
    args = parser.parse_args()
    result = main(args.rays)
    path = write_results("rays", result)
    for name, row in result["methods"].items():
        print(
            f"{name:26s} {row['us_per_ray']:10.1f} us/ray  {row['evaluations_per_ray']:9.0f} evals/ray  "
            f"max err {row['max_error_m']:.2e} m  p99 {row['p99_error_m']:.2e} m"
        )
    print("ratios", result["ratios"], "->", path)
