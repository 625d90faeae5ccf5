"""The interactive editor's latencies (refracta.widgets.EditorModel, the model behind MirageEditor),
on the hot road at the sizes an editor shows (320x120, 640x240, 1280x480).

Per size, best of REPEAT runs:
  preview_s  -- from a render request to the quarter-resolution preview (goal: <= 0.5 s on 2 cores),
  full_s     -- ... to the full-resolution image (preview included),
  supersede_s -- from a camera move while the full image is rendering to the new view's preview
               (the running render cancelled through its progress callable, then the preview),
  png_s      -- encoding the full image for the browser (view: canvas.png_bytes).
Solves, at 320x120, from the request to the solved atmosphere applied (solve_s; solver_s:
EditResult.time, the solver alone) and to the full image through it (solve_to_image_s; the ray fan
figure is drawn meanwhile):
  notebook02 -- notebook 02's two pairs on the blue car, free surface_dt and surface_depth;
  truth3     -- three pairs in the mirage band met exactly by a 16 K road, free surface_dt;
  truth4_2free -- four such pairs, free surface_dt and surface_depth.

    python benchmarks/bench_editor.py     -> benchmarks/results/editor.json
"""

from __future__ import annotations

import threading
import time

import numpy as np
from _common import write_results

import refracta
from refracta import examples
from refracta.widgets import EditorModel
from refracta.widgets.canvas import png_bytes

SIZES = [(320, 120), (640, 240), (1280, 480)]
REPEAT = 3
PREVIEW_GOAL = 0.5  # [s] the goal for the quarter-resolution preview on 2 cores


class Clock:
    """Times from a start to the model's image notifications (level, seconds since start)."""

    def __init__(self, model: EditorModel):
        self.events, self.start = [], 0.0
        self.changed = threading.Condition()
        model.observe(self._seen(model))

    def _seen(self, model):
        def seen(what):
            if what == "image":
                with self.changed:
                    self.events.append((model.images["curved"].level, model.camera, time.perf_counter() - self.start))
                    self.changed.notify_all()

        return seen

    def reset(self):
        self.events, self.start = [], time.perf_counter()

    def first(self, level, camera=None):
        return next(t for lv, cam, t in self.events if lv == level and (camera is None or cam is camera))


def render_latencies(road) -> dict:
    model = EditorModel(
        road.scene, road.camera, road.field, stop_height=0.0, max_length=road.max_length, autorender=False
    )
    clock = Clock(model)
    model.render()  # warm-up: the eye's elevation table, caches
    model.wait()
    preview, full, supersede, png = [], [], [], []
    for _ in range(REPEAT):
        clock.reset()
        model.render()
        model.wait()
        preview.append(clock.first("preview"))
        full.append(clock.first("full"))
        # a camera move while the full image renders: until the new view's preview
        clock.reset()
        model.render()
        with clock.changed:
            clock.changed.wait_for(lambda: any(lv == "preview" for lv, _, _ in clock.events))
        moved_at = time.perf_counter()
        model.wheel(0.2)
        moved = model.camera
        model.wait()
        supersede.append(clock.first("preview", moved) - (moved_at - clock.start))
        model.undo()
        model.wait()
        start = time.perf_counter()
        png_bytes(model.images["curved"].pixels)
        png.append(time.perf_counter() - start)
    model.close()
    return {
        "preview_s": min(preview),
        "full_s": min(full),
        "supersede_s": min(supersede),
        "png_s": min(png),
        "preview_goal_met": min(preview) <= PREVIEW_GOAL,
    }


def truth_pairs(road, count):
    truth = road.field.with_params(surface_dt=16.0)
    pairs = []
    for v in np.linspace(61.9, 64.5, count):
        origin, direction = road.camera.ray(160.0, v)
        path = refracta.trace_ray(truth, origin, direction, tol=1e-10, max_length=400.0, stop_height=0.0)
        pairs.append(((160.0, float(v)), path.point_at(350.0)[0]))
    return pairs


def solve_latencies(road) -> dict:
    camera, scene = road.camera, road.scene
    cases = {
        "notebook02": (
            ["surface_dt", "surface_depth"],
            [((180.4, 64.06), camera.pick(scene, 180.4, 63.9)), ((180.4, 55.92), camera.pick(scene, 180.4, 55.9))],
        ),
        "truth3": (["surface_dt"], truth_pairs(road, 3)),
        "truth4_2free": (["surface_dt", "surface_depth"], truth_pairs(road, 4)),
    }
    rows = {}
    for name, (free, pairs) in cases.items():
        times, to_image, solver, success = [], [], [], None
        for _ in range(REPEAT):
            model = EditorModel(
                scene, camera, road.field, free, stop_height=0.0, max_length=road.max_length, autorender=False
            )
            for destination, source in pairs:
                model.add_pair(destination, source)
            solved = threading.Event()
            model.observe(
                lambda what, model=model, solved=solved: what == "result" and model.result is not None and solved.set()
            )
            clock = Clock(model)
            clock.reset()
            model.solve()
            solved.wait()
            times.append(time.perf_counter() - clock.start)
            model.wait()
            to_image.append(clock.first("full"))
            success = bool(model.result.success)
            solver.append(model.result.time)
            model.close()
        rows[name] = {
            "pairs": len(pairs),
            "free": free,
            "solve_s": min(times),
            "solver_s": min(solver),
            "solve_to_image_s": min(to_image),
            "success": success,
        }
    return rows


def main() -> dict:
    renders = {}
    for width, height in SIZES:
        road = examples.hot_road(width, height)
        row = render_latencies(road)
        renders[f"{width}x{height}"] = row
        print(
            f"hot road {width}x{height}: preview {row['preview_s']:.3f} s, full {row['full_s']:.3f} s, "
            f"camera move -> preview {row['supersede_s']:.3f} s, PNG {row['png_s'] * 1e3:.1f} ms"
        )
    solves = solve_latencies(examples.hot_road(320, 120))
    for name, row in solves.items():
        print(
            f"solve {name}: {row['pairs']} pairs, free {row['free']}: {row['solve_s']:.3f} s "
            f"(the solver {row['solver_s']:.3f} s) "
            f"(image after it {row['solve_to_image_s']:.3f} s), success {row['success']}"
        )
    payload = {"renders": renders, "solves": solves, "preview_goal_s": PREVIEW_GOAL, "repeat": REPEAT}
    print(f"wrote {write_results('editor', payload)}")
    return payload


if __name__ == "__main__":
    main()
